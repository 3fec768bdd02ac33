#pragma once
// Step control of the nonlinear contact loop: which load factor to try next, and what a
// rejected attempt does. A step that does not converge is halved and retried, at most
// "Maximum cutbacks" times in a row, and never below nominal / 2^"Maximum cutbacks"; after a
// converged step the increment grows again (doubled) towards the nominal 1 / "Load steps". The
// floor ends a run that would otherwise creep towards a load it cannot pass, each converged small
// step renewing its cut-backs (a Coulomb run took 835 steps of down to 1e-7 towards 0.9569). The
// state lives in the run's NonlinearHistory, so a restart continues with the increment the
// interrupted run would have tried.
#include "contact_NonlinearHistory.hpp"

namespace contact {

class LoadStepControl {
 public:
  LoadStepControl(NonlinearHistory& history, int loadSteps, int maxCutbacks, int stopAfter);

  bool finished() const;       // load factor 1 reached
  bool stopRequested() const;  // "Stop after step" reached
  int nextStep() const;        // the step to attempt (1-based)
  double nextLoadFactor() const;
  int cutbacks() const { return cutbacks_; }  // rejected attempts of the step to attempt

  // A converged attempt at nextLoadFactor(): the history's step and load factor advance (the
  // caller appends its StepRecord), the increment grows back towards the nominal one.
  void accept();
  // A rejected attempt: halves the increment it tried and returns true, or returns false when
  // the allowed cut-backs are used up or the halved increment would fall below
  // smallestIncrement() (the run fails).
  bool reject();
  double smallestIncrement() const;  // nominal / 2^maxCutbacks
  // The last reject() returned false because of smallestIncrement(), not the cut-backs' count.
  bool belowSmallest() const { return belowSmallest_; }

 private:
  NonlinearHistory& history_;
  double nominal_;
  int maxCutbacks_, stopAfter_;
  int cutbacks_ = 0;
  bool belowSmallest_ = false;
};

}  // namespace contact
