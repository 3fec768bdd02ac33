// Step control of the nonlinear contact loop: nominal increments, halving on rejection up to
// "Maximum cutbacks" in a row, growth back to the nominal increment, stop after a step, and a
// restarted history continuing with the increment it saved.
#include <Teuchos_UnitTestHarness.hpp>

#include "contact_LoadStepControl.hpp"

namespace {

using contact::LoadStepControl;
using contact::NonlinearHistory;

TEUCHOS_UNIT_TEST(LoadStepControl, NominalSteps) {
  NonlinearHistory h;
  h.stepSize = 1.0 / 4;
  LoadStepControl c(h, 4, 2, 0);
  int steps = 0;
  while (!c.finished()) {
    TEST_EQUALITY(c.nextStep(), steps + 1);
    TEST_FLOATING_EQUALITY(c.nextLoadFactor(), (steps + 1) / 4.0, 1e-15);
    c.accept();
    ++steps;
  }
  TEST_EQUALITY(steps, 4);
  TEST_EQUALITY(h.step, 4);
  TEST_FLOATING_EQUALITY(h.loadFactor, 1.0, 1e-15);
}

TEUCHOS_UNIT_TEST(LoadStepControl, CutBackAndGrowBack) {
  NonlinearHistory h;
  h.stepSize = 0.5;
  LoadStepControl c(h, 2, 2, 0);
  // Step 1 at 0.5 rejected twice: 0.25, then 0.125; a third rejection exceeds the 2 allowed.
  TEST_ASSERT(c.reject());
  TEST_FLOATING_EQUALITY(c.nextLoadFactor(), 0.25, 1e-15);
  TEST_ASSERT(c.reject());
  TEST_FLOATING_EQUALITY(c.nextLoadFactor(), 0.125, 1e-15);
  TEST_EQUALITY(c.cutbacks(), 2);
  {  // a third rejection: the count is used up (the message then names the count, not the floor)
    NonlinearHistory fresh;
    fresh.stepSize = 0.5;
    LoadStepControl d(fresh, 2, 2, 0);
    TEST_ASSERT(d.reject() && d.reject() && !d.reject());
    TEST_ASSERT(!d.belowSmallest());
  }
  c.accept();  // converged at 0.125: the count resets, the increment doubles to 0.25
  TEST_EQUALITY(c.cutbacks(), 0);
  TEST_EQUALITY(h.step, 1);
  TEST_FLOATING_EQUALITY(c.nextLoadFactor(), 0.375, 1e-15);
  c.accept();  // 0.375; the increment grows to the nominal 0.5, never beyond it
  TEST_FLOATING_EQUALITY(c.nextLoadFactor(), 0.875, 1e-15);
  c.accept();
  TEST_FLOATING_EQUALITY(c.nextLoadFactor(), 1.0, 1e-15);  // clipped at the full load
  // The increment tried was 0.125, the smallest allowed (0.5 / 2^2): halving it would go below.
  TEST_ASSERT(!c.reject());
  TEST_ASSERT(c.belowSmallest());
  TEST_EQUALITY(c.cutbacks(), 0);
}

TEUCHOS_UNIT_TEST(LoadStepControl, ClippedIncrementHalved) {
  NonlinearHistory h;
  h.stepSize = 0.5;
  h.loadFactor = 0.75;
  LoadStepControl c(h, 2, 4, 0);
  TEST_FLOATING_EQUALITY(c.smallestIncrement(), 0.03125, 1e-15);
  TEST_FLOATING_EQUALITY(c.nextLoadFactor(), 1.0, 1e-15);  // 0.25 tried, clipped
  // Halving the nominal 0.5 would try 1.0 again; the increment tried is halved instead.
  TEST_ASSERT(c.reject());
  TEST_FLOATING_EQUALITY(c.nextLoadFactor(), 0.875, 1e-15);
}

TEUCHOS_UNIT_TEST(LoadStepControl, NoCreepBelowSmallestIncrement) {
  // A load the run cannot pass (0.8): every attempt beyond it is rejected. Each converged small
  // step renews the cut-backs, and without the floor the run crept towards 0.8 step after step.
  NonlinearHistory h;
  h.stepSize = 0.5;
  LoadStepControl c(h, 2, 2, 0);  // smallest increment 0.125
  int attempts = 0;
  bool stopped = false;
  while (!stopped && attempts < 1000) {
    ++attempts;
    if (c.nextLoadFactor() < 0.8)
      c.accept();
    else
      stopped = !c.reject();
  }
  TEST_ASSERT(stopped);
  TEST_ASSERT(c.belowSmallest());
  TEST_ASSERT(attempts < 10);
  TEST_FLOATING_EQUALITY(h.loadFactor, 0.75, 1e-15);
}

TEUCHOS_UNIT_TEST(LoadStepControl, StopAfterStepAndRestart) {
  NonlinearHistory h;
  h.stepSize = 1.0 / 3;
  LoadStepControl c(h, 3, 4, 1);
  TEST_ASSERT(!c.stopRequested());
  c.accept();
  TEST_ASSERT(c.stopRequested());
  TEST_ASSERT(!c.finished());
  // A restart continues from the saved history (step, load factor, increment).
  NonlinearHistory saved = h;
  LoadStepControl again(saved, 3, 4, 0);
  TEST_EQUALITY(again.nextStep(), 2);
  TEST_FLOATING_EQUALITY(again.nextLoadFactor(), 2.0 / 3, 1e-15);
}

}  // namespace
