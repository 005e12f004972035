#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bipednav/planning/local/moving_obstacles.hpp"
#include "moving_obstacle_test_utils.hpp"

namespace bipednav::planning::local {

TEST(MovingObstacles, StaticBoxSeenFromAPassingRobotNeverMoves) {
  // A 0.4 m box at the origin seen from a robot passing 1 m in front of it at 0.4 m/s, and a 0.2 m
  // post beside its path: the faces seen of the box turn from left and front to front to front and
  // right (its blob's centroid slides 0.2 m), points drop out and jitter by up to 2 cm, and the
  // post's centroid jitters by up to 4 cm (partial segmentation).
  MovingObstacleTracker tracker(enabled_tracking());
  const double half = 0.2;
  for (int k = 0; k <= 300; ++k) {  // 30 s: the robot passes the box, turns and passes it again
    const double t = 0.1 * k;
    const double u = std::fmod(0.4 * t, 12.0);
    const Eigen::Vector2d robot(u < 6.0 ? u - 3.0 : 9.0 - u, -1.0);
    std::vector<Eigen::Vector2d> pts;
    int n = 0;
    const auto keep = [&](int i) { return (i * 7 + k * 3) % 5 != 0; };  // one point in five drops out
    for (double s = -half; s <= half + 1e-9; s += 0.02, ++n) {
      const double j = 0.02 * std::sin(2.3 * n + 1.1 * k);
      if (keep(n)) pts.emplace_back(s, -half + j);                           // front face: always seen
      if (robot.x() < -half && keep(n + 1)) pts.emplace_back(-half + j, s);  // left face
      if (robot.x() > half && keep(n + 2)) pts.emplace_back(half + j, s);    // right face
    }
    const Eigen::Vector2d post(1.5 + 0.04 * std::sin(0.9 * k), 1.0 + 0.04 * std::cos(1.3 * k));
    add_square(pts, post, 0.2, k);
    tracker.update(pts, robot, t);
    EXPECT_TRUE(tracker.moving(t).empty()) << "t = " << t;
  }
  EXPECT_EQ(tracker.tracks().size(), 2u);
}

TEST(MovingObstacles, LatchedDisplacementKeepsALoopingBoxMovingPastItsTrackStart) {
  // A 0.3 m box driven round a 1.5 m square at 0.5 m/s (12 s a lap), first seen in the middle of
  // the bottom edge: one lap later it passes where its track began at full speed
  // (hexagon_dynamic/turtlebot3 seed 20's box). From its first centroid alone it is static within
  // min_displacement_m of it; with latch_displacement_m it stays moving.
  MovingObstacleParams latched = enabled_tracking(), unlatched = enabled_tracking();
  latched.latch_displacement_m = 1.0;
  unlatched.latch_displacement_m = 0.0;
  MovingObstacleTracker on(latched), off(unlatched);
  const double side = 1.5, speed = 0.5;
  const Eigen::Vector2d centre(2.0, 0.0);
  const auto box_at = [&](double t) {  // counter-clockwise from the bottom edge's middle
    const double u = std::fmod(speed * t + 0.5 * side, 4.0 * side);
    const double h = 0.5 * side;
    if (u < side) return Eigen::Vector2d(centre.x() - h + u, centre.y() - h);
    if (u < 2.0 * side) return Eigen::Vector2d(centre.x() + h, centre.y() - h + (u - side));
    if (u < 3.0 * side) return Eigen::Vector2d(centre.x() + h - (u - 2.0 * side), centre.y() + h);
    return Eigen::Vector2d(centre.x() - h, centre.y() + h - (u - 3.0 * side));
  };
  const Eigen::Vector2d start = box_at(0.0);
  double first_moving_s = -1.0;
  int id = -1, off_static_near_start = 0, near_start = 0;
  for (int k = 0; k <= 300; ++k) {  // 30 s: two passes of the start
    const double t = 0.1 * k;
    const Eigen::Vector2d box = box_at(t);
    std::vector<Eigen::Vector2d> pts;
    add_square(pts, box, 0.3, k);
    on.update(pts, {0.0, 0.0}, t);
    off.update(pts, {0.0, 0.0}, t);
    const auto moving = on.moving(t);
    if (first_moving_s < 0.0) {
      if (!moving.empty()) first_moving_s = t, id = moving[0].id;
      continue;
    }
    ASSERT_EQ(moving.size(), 1u) << "t = " << t << " s, box at " << box.transpose();
    EXPECT_EQ(moving[0].id, id);
    EXPECT_LT((moving[0].position - box).norm(), 0.15) << "t = " << t;
    if (t > 6.0 && (box - start).norm() < 0.1) {
      ++near_start;
      EXPECT_TRUE(moving[0].displaced) << "t = " << t;
      if (off.moving(t).empty()) ++off_static_near_start;
    }
  }
  EXPECT_GT(first_moving_s, 0.0);
  EXPECT_LT(first_moving_s, 1.5);
  // Both passes (12 and 24 s), 0.4 s each (0.1 m either side at 0.5 m/s): the track from its
  // first centroid alone is static at every one of those cycles.
  EXPECT_GE(near_start, 6);
  EXPECT_EQ(off_static_near_start, near_start);
  ASSERT_EQ(off.tracks().size(), 1u);
  EXPECT_FALSE(off.tracks()[0].displaced);  // off: never latched
}

TEST(MovingObstacles, WanderingCentroidShorterThanTheLatchDistanceNeverLatches) {
  // A piece of a wall seen at grazing incidence: its centroid slides to and fro 0.6 m along the
  // wall at up to 0.24 m/s (fast and farther than min_displacement_m from its origin at times, so it
  // counts as moving then), never 1 m from where its track began: it never latches, and the tracker
  // with latch_displacement_m classes it as the one without does at every cycle.
  MovingObstacleParams latched = enabled_tracking(), unlatched = enabled_tracking();
  latched.latch_displacement_m = 1.0;
  unlatched.latch_displacement_m = 0.0;
  MovingObstacleTracker on(latched), off(unlatched);
  int moving_cycles = 0, static_cycles_after_moving = 0;
  for (int k = 0; k <= 300; ++k) {
    const double t = 0.1 * k;
    const double x = 1.5 + 0.3 - 0.3 * std::cos(0.8 * t);  // 0.6 m travel, peak speed 0.24 m/s
    const double y = 1.0 + 0.02 * std::sin(1.9 * k);
    std::vector<Eigen::Vector2d> pts;
    add_square(pts, {x, y}, 0.2, k);
    on.update(pts, {0.0, 0.0}, t);
    off.update(pts, {0.0, 0.0}, t);
    const auto m_on = on.moving(t), m_off = off.moving(t);
    ASSERT_EQ(m_on.size(), m_off.size()) << "t = " << t;
    if (!m_on.empty()) ++moving_cycles;
    if (moving_cycles > 0 && m_on.empty()) ++static_cycles_after_moving;
    for (const auto& tr : on.tracks()) EXPECT_FALSE(tr.displaced) << "t = " << t;
  }
  EXPECT_EQ(on.tracks().size(), 1u);
  // It is taken for moving while it is away from its origin, and for static again when it comes
  // back (the latch would have kept it moving).
  EXPECT_GT(moving_cycles, 0);
  EXPECT_GT(static_cycles_after_moving, 0);
}

}  // namespace bipednav::planning::local
