#include "bipednav/tracking/mot_metrics.hpp"

#include <gtest/gtest.h>

namespace bipednav::tracking {

TEST(ClearMot, CountsMatchesMissesFalsePositivesAndSwitches) {
  ClearMot mot(0.5, 1.0);
  const auto obj = [](int id, double x, double vx = 0.0) { return MotObject{id, {x, 0.0}, {vx, 0.0}}; };
  // t 0: object 1 unmatched (its hypothesis is 0.6 m away: a miss and a false positive).
  mot.add_frame(0.0, {obj(1, 0.0)}, {}, {obj(10, 0.6)});
  // t 0.1, 0.2: hypothesis 10 on it, 0.1 m off, velocity 0.2 m/s off.
  mot.add_frame(0.1, {obj(1, 0.0, 1.0)}, {}, {obj(10, 0.1, 1.2)});
  mot.add_frame(0.2, {obj(1, 0.0, 1.0)}, {}, {obj(10, 0.1, 1.2)});
  // t 0.3: hypothesis 11 nearer, but 10 is still within 0.5 m: the match is kept, 11 is a false
  // positive.
  mot.add_frame(0.3, {obj(1, 0.0, 1.0)}, {}, {obj(11, 0.0, 1.0), obj(10, 0.1, 1.2)});
  // t 0.4: 10 gone; 11 takes over: an identity switch. A hypothesis on an ignored object counts
  // neither way.
  mot.add_frame(0.4, {obj(1, 0.0, 1.0)}, {obj(2, 5.0)}, {obj(11, 0.0, 1.0), obj(12, 5.2)});
  // t 0.5: a hypothesis outside the evaluated region matching nothing counts neither way.
  mot.add_frame(0.5, {obj(1, 0.0, 1.0)}, {}, {obj(11, 0.0, 1.0), obj(13, 9.0)}, {1, 0});
  // t 0.6: object 1 out of view; its hypothesis 11, coasting 2 m off it, counts neither way.
  mot.add_frame(0.6, {}, {obj(1, 0.0, 1.0)}, {obj(11, 2.0, 1.0)});
  const MotSummary s = mot.summary();
  EXPECT_EQ(s.truths, 6);
  EXPECT_EQ(s.matches, 5);
  EXPECT_EQ(s.misses, 1);
  EXPECT_EQ(s.false_positives, 2);
  EXPECT_EQ(s.id_switches, 1);
  EXPECT_DOUBLE_EQ(s.mota(), 1.0 - 4.0 / 6.0);
  EXPECT_NEAR(s.position_rmse_m, std::sqrt(3 * 0.01 / 5.0), 1e-12);
  EXPECT_NEAR(s.velocity_rmse_mps, std::sqrt(3 * 0.04 / 5.0), 1e-12);
  // One appearance, picked up 0.1 s after it began.
  EXPECT_EQ(s.appearances, 1);
  EXPECT_EQ(s.appearances_picked_up, 1);
  EXPECT_NEAR(s.mean_pickup_s, 0.1, 1e-12);
}

TEST(ClearMot, AnObjectBackInViewAfterTheGapAppearsAgain) {
  ClearMot mot(0.5, 1.0);
  const MotObject o{1, {0.0, 0.0}, {0.0, 0.0}}, h{7, {0.0, 0.0}, {0.0, 0.0}};
  mot.add_frame(0.0, {o}, {}, {h});
  mot.add_frame(0.5, {o}, {}, {});   // counted, not matched: same appearance
  mot.add_frame(2.0, {o}, {}, {});   // back after 1.5 s: a new appearance ...
  mot.add_frame(2.3, {o}, {}, {h});  // ... picked up 0.3 s later, by the same hypothesis
  const MotSummary s = mot.summary();
  EXPECT_EQ(s.appearances, 2);
  EXPECT_EQ(s.appearances_picked_up, 2);
  EXPECT_NEAR(s.max_pickup_s, 0.3, 1e-12);
  EXPECT_EQ(s.id_switches, 0);
  EXPECT_EQ(ClearMot().summary().mota(), 1.0);
  // Pooled with itself: the same ratios, twice the counts.
  const MotSummary twice = pool({s, s});
  EXPECT_EQ(twice.truths, 2 * s.truths);
  EXPECT_EQ(twice.appearances, 4);
  EXPECT_DOUBLE_EQ(twice.mota(), s.mota());
  EXPECT_NEAR(twice.max_pickup_s, 0.3, 1e-12);
  EXPECT_NEAR(twice.mean_pickup_s, s.mean_pickup_s, 1e-12);
}

TEST(ClearMot, VelocityErrorsOfTurningObjectsAreSummedApart) {
  ClearMot mot(0.5, 1.0);
  MotObject steady{1, {0.0, 0.0}, {1.0, 0.0}}, turned = steady;
  turned.velocity = {-1.0, 0.0};  // reversed on the spot: the hypothesis still says +1 m/s
  turned.turning = true;
  const MotObject h{7, {0.0, 0.0}, {1.1, 0.0}};
  mot.add_frame(0.0, {steady}, {}, {h});
  mot.add_frame(0.1, {steady}, {}, {h});
  mot.add_frame(0.2, {turned}, {}, {h});
  const MotSummary s = mot.summary();
  EXPECT_EQ(s.matches, 3);
  EXPECT_EQ(s.matches_turning, 1);
  EXPECT_NEAR(s.velocity_rmse_mps, std::sqrt((0.01 + 0.01 + 2.1 * 2.1) / 3.0), 1e-12);
  EXPECT_NEAR(s.velocity_rmse_steady_mps, 0.1, 1e-12);
  // Pooled with a part without matches: unchanged.
  const MotSummary pooled = pool({s, ClearMot().summary()});
  EXPECT_EQ(pooled.matches_turning, 1);
  EXPECT_NEAR(pooled.velocity_rmse_steady_mps, 0.1, 1e-12);
}

}  // namespace bipednav::tracking
