// The Newton loop's tests on residual histories with known answers: convergence at the
// tolerance, a stall when a residual is above half the previous one, hopeless when the smallest
// residual has not halved in the last kStallWindow iterations or, where asked, when a triangle is
// inverted while the residual stagnates, and the iteration limit.
#include "engine/solve/newton_monitor.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pfem {
namespace {

constexpr int kWindow = NewtonMonitor::kStallWindow;

TEST(NewtonMonitor, ConvergesAtTheTolerance) {
  NewtonMonitor m(1e-10, 50);
  for (int k = 0; k < 10; ++k) {
    m.record(std::pow(10.0, -k));
    EXPECT_FALSE(m.converged());
    EXPECT_FALSE(m.stalled());
  }
  m.record(1e-10);  // at the tolerance counts
  EXPECT_TRUE(m.converged());
  EXPECT_EQ(m.iteration(), 10);
}

TEST(NewtonMonitor, StalledAboveHalfThePrevious) {
  NewtonMonitor m(1e-10, 50);
  m.record(1.0);
  EXPECT_FALSE(m.stalled());  // the first iterate has no previous one
  m.record(0.5);
  EXPECT_FALSE(m.stalled());  // exactly half: still contracting enough
  m.record(0.26);
  EXPECT_TRUE(m.stalled());
  m.record(2.0);  // growing
  EXPECT_TRUE(m.stalled());
}

TEST(NewtonMonitor, HopelessWhenTheBestHasNotHalvedInTheWindow) {
  // A contraction of 0.95 a step: 0.95^10 = 0.60 > 0.5, hopeless from iteration 2 kWindow on,
  // never before (the first window is always granted).
  NewtonMonitor slow(1e-10, 50);
  for (int it = 0; it <= 2 * kWindow; ++it) {
    slow.record(std::pow(0.95, it));
    EXPECT_EQ(slow.hopeless(), it == 2 * kWindow) << it;
  }
  // 0.9 a step: 0.9^10 = 0.35, never hopeless.
  NewtonMonitor steady(1e-10, 50);
  for (int it = 0; it <= 4 * kWindow; ++it) {
    steady.record(std::pow(0.9, it));
    EXPECT_FALSE(steady.hopeless()) << it;
  }
  // Cycling after a good start: the best so far counts, not the last residual. The best reached
  // 1e-3 at iteration 5 and nothing later is below it.
  NewtonMonitor cycling(1e-10, 50);
  for (int it = 0; it <= 2 * kWindow; ++it) cycling.record(it <= 5 ? std::pow(0.25, it) : (it % 2 ? 1e-2 : 2e-3));
  EXPECT_TRUE(cycling.hopeless());
}

TEST(NewtonMonitor, HopelessWhenInvertedAndStagnatingIfAsked) {
  // A plateau at 1e-3 from iteration 3 on (the best falls 10x over no 3 iterations from then):
  // hopeless at kInvertedFrom with a triangle inverted there, never without the inversion, never
  // when not asked to give up so (a step's last retry), and not on an inverted iterate while the
  // residual still falls 10x in 3 iterations (0.4 a step: 0.064).
  const auto plateau = [](int it) { return it < 3 ? std::pow(10.0, -it) : 1e-3 * (1.0 + 0.1 * (it % 2)); };
  NewtonMonitor asked(1e-10, 50, true), unasked(1e-10, 50, false), upright(1e-10, 50, true);
  for (int it = 0; it <= NewtonMonitor::kInvertedFrom; ++it) {
    asked.record(plateau(it), it >= 2);
    unasked.record(plateau(it), it >= 2);
    upright.record(plateau(it), false);
    EXPECT_EQ(asked.hopeless(), it == NewtonMonitor::kInvertedFrom) << it;
    EXPECT_EQ(asked.inverted_and_stagnating(), it == NewtonMonitor::kInvertedFrom) << it;
    EXPECT_FALSE(unasked.hopeless()) << it;
    EXPECT_FALSE(upright.hopeless()) << it;
  }
  NewtonMonitor converging(1e-10, 50, true);
  for (int it = 0; it <= 12; ++it) {
    converging.record(std::pow(0.4, it), true);
    EXPECT_FALSE(converging.hopeless()) << it;
  }
  // The smallest residual so far counts: after a best of 1e-3 at iteration 3, a bounce to 1e-1
  // that falls tenfold again is no progress.
  NewtonMonitor bouncing(1e-10, 50, true);
  for (const double r : {1.0, 1e-1, 1e-2, 1e-3, 1e-1, 1e-2, 2e-3}) bouncing.record(r, true);
  EXPECT_TRUE(bouncing.hopeless());  // best 1e-3 at iterations 3..6: not 10x lower than at 3
}

TEST(NewtonMonitor, OutOfIterationsAtTheLimit) {
  NewtonMonitor m(1e-10, 3);
  for (int it = 0; it < 3; ++it) {
    m.record(0.1);
    EXPECT_FALSE(m.out_of_iterations());
  }
  m.record(0.1);
  EXPECT_EQ(m.iteration(), 3);
  EXPECT_TRUE(m.out_of_iterations());
}

}  // namespace
}  // namespace pfem
