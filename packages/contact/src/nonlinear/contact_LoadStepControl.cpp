#include "contact_LoadStepControl.hpp"

#include <algorithm>
#include <cmath>

namespace contact {

LoadStepControl::LoadStepControl(NonlinearHistory& history, int loadSteps, int maxCutbacks,
                                 int stopAfter)
    : history_(history),
      nominal_(1.0 / loadSteps),
      maxCutbacks_(maxCutbacks),
      stopAfter_(stopAfter) {}

bool LoadStepControl::finished() const {
  return !(history_.loadFactor < 1.0 - 1e-12);
}

bool LoadStepControl::stopRequested() const {
  return stopAfter_ > 0 && history_.step >= stopAfter_;
}

int LoadStepControl::nextStep() const {
  return history_.step + 1;
}

double LoadStepControl::nextLoadFactor() const {
  return std::min(1.0, history_.loadFactor + history_.stepSize);
}

void LoadStepControl::accept() {
  history_.loadFactor = nextLoadFactor();
  history_.step = nextStep();
  // After a cut-back, grow the increment again towards the nominal one.
  history_.stepSize = std::min(nominal_, 2.0 * history_.stepSize);
  cutbacks_ = 0;
}

double LoadStepControl::smallestIncrement() const {
  return std::ldexp(nominal_, -maxCutbacks_);
}

bool LoadStepControl::reject() {
  // The increment tried, which the full load may have clipped: halving the nominal one instead
  // would try the same load factor again.
  const double halved = 0.5 * std::min(history_.stepSize, 1.0 - history_.loadFactor);
  belowSmallest_ = false;
  if (cutbacks_ >= maxCutbacks_) return false;
  belowSmallest_ = halved < smallestIncrement() * (1.0 - 1e-12);
  if (belowSmallest_) return false;
  ++cutbacks_;
  history_.stepSize = halved;
  return true;
}

}  // namespace contact
