#include "contact_LoadStepControl.hpp"

#include <algorithm>

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

bool LoadStepControl::reject() {
  if (cutbacks_ >= maxCutbacks_) return false;
  ++cutbacks_;
  history_.stepSize *= 0.5;
  return true;
}

}  // namespace contact
