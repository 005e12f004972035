#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/moving_obstacles.hpp"
#include "local_test_utils.hpp"

namespace bipednav::planning::local {

namespace {

// The outline of an axis-aligned square of side `side` centred at c, a point every 2 cm, with a
// deterministic jitter of up to 1 cm.
void add_square(std::vector<Eigen::Vector2d>& pts, const Eigen::Vector2d& c, double side, int salt) {
  const int n = static_cast<int>(side / 0.02);
  for (int i = 0; i <= n; ++i) {
    const double s = -0.5 * side + i * 0.02;
    const double j = 0.01 * std::sin(1.7 * i + 0.9 * salt);
    pts.emplace_back(c.x() + s, c.y() - 0.5 * side + j);
    pts.emplace_back(c.x() + s, c.y() + 0.5 * side - j);
    pts.emplace_back(c.x() - 0.5 * side + j, c.y() + s);
    pts.emplace_back(c.x() + 0.5 * side - j, c.y() + s);
  }
}

void add_wall(std::vector<Eigen::Vector2d>& pts, double x0, double x1, double y) {
  for (double x = x0; x <= x1; x += 0.03) pts.emplace_back(x, y);
}

MovingObstacleParams enabled_tracking() {
  MovingObstacleParams p;
  p.enabled = true;
  return p;
}

const TrackedObstacle* track_near(const MovingObstacleTracker& t, const Eigen::Vector2d& p) {
  for (const auto& tr : t.tracks())
    if ((tr.position - p).norm() < 0.2) return &tr;
  return nullptr;
}

std::shared_ptr<MovingObstacleTracker> tracker_with(const Eigen::Vector2d& start, const Eigen::Vector2d& velocity,
                                                    double until_s) {
  auto t = std::make_shared<MovingObstacleTracker>(enabled_tracking());
  for (double s = 0.0; s <= until_s + 1e-9; s += 0.1) {
    std::vector<Eigen::Vector2d> pts;
    add_square(pts, start + velocity * s, 0.15, static_cast<int>(s * 10));
    t->update(pts, {0.0, 0.0}, s);
  }
  return t;
}

// Digit's range sensors (config/digit.yaml): a VLP-16 at 1.474 m and two D430s at the pelvis
// (0.95 m), pitched 45 deg down, facing forward and back.
RobotProfile digit_sensors() {
  RobotProfile r;
  const double pitch = 0.25 * M_PI;
  r.sensors = {{"lidar", "vlp16", 0.0, 0.0, 1.474},
               {"depth_front", "d430", 0.1, 0.0, 0.95, 0.0, pitch, 0.0},
               {"depth_back", "d430", -0.1, 0.0, 0.95, 0.0, pitch, M_PI}};
  return r;
}

SensorVisibility digit_visibility() { return SensorVisibility(digit_sensors(), SensorVisibilityParams{}); }

MovingObstacleParams coasting_tracking() {
  MovingObstacleParams p = enabled_tracking();
  p.coast_in_blind_zone = true;
  return p;
}

// The blob of a 0.5 m cube centred at c (the outline a sensor sees of it).
Blob cube_blob(const Eigen::Vector2d& c) { return Blob{c, 0.35, 0.5, 40}; }

}  // namespace

TEST(MovingObstacles, ClusterBlobsSeparatesSmallBlobsAndDropsWalls) {
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {1.0, 1.0}, 0.15, 0);
  add_square(pts, {2.0, -1.0}, 0.4, 1);
  add_wall(pts, -3.0, 3.0, 2.5);         // a wall: too large to be a blob
  pts.emplace_back(-1.5, -1.5);          // a single return: noise
  pts.emplace_back(std::nan(""), 0.0);   // skipped
  add_square(pts, {9.0, 0.0}, 0.15, 2);  // out of range
  const auto blobs = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking());
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_NEAR(blobs[0].centroid.x(), 1.0, 0.02);
  EXPECT_NEAR(blobs[0].centroid.y(), 1.0, 0.02);
  EXPECT_NEAR(blobs[1].centroid.x(), 2.0, 0.02);
  EXPECT_NEAR(blobs[1].centroid.y(), -1.0, 0.02);
  EXPECT_GT(blobs[1].radius_m, blobs[0].radius_m);
}

TEST(MovingObstacles, ClusterBlobsSameWhateverTheBinWindow) {
  // The bins in range are counted on a grid over their window, or hashed when the window is too
  // large for a grid (a huge range): the same blobs, in the same order, bit for bit.
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {1.0, 1.0}, 0.15, 0);
  add_square(pts, {2.0, -1.0}, 0.4, 1);
  add_square(pts, {-1.2, 0.3}, 0.2, 2);
  add_square(pts, {1.1, 1.25}, 0.1, 3);  // touches the first square's bins: one blob
  add_wall(pts, -3.0, 3.0, 2.5);
  pts.emplace_back(-1.5, -1.5);
  const auto near = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking());
  ASSERT_EQ(near.size(), 3u);
  add_square(pts, {900.0, -700.0}, 0.15, 4);  // 16000 x 7000 bins apart
  auto far_params = enabled_tracking();
  far_params.max_range_m = 2000.0;
  const auto all = cluster_blobs(pts, {0.0, 0.0}, far_params);
  ASSERT_EQ(all.size(), 4u);
  for (std::size_t i = 0; i < near.size(); ++i) {
    EXPECT_EQ(all[i].centroid, near[i].centroid);
    EXPECT_EQ(all[i].radius_m, near[i].radius_m);
    EXPECT_EQ(all[i].points, near[i].points);
  }
  EXPECT_NEAR(all[3].centroid.x(), 900.0, 0.02);
}

TEST(MovingObstacles, BoxBesideAPostInALaneStaysItsOwnBlob) {
  // hexagon_dynamic: the 0.15 m box in a 0.8 m lane between r = 0.15 m cylinders (0.325 m gaps).
  // Merged with a cylinder its centroid would jump and its track be lost.
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {0.55, 0.0}, 0.15, 0);
  for (int i = 0; i < 64; ++i) {
    const double a = 2.0 * M_PI * i / 64.0;
    for (const double cx : {0.0, 1.1}) pts.emplace_back(cx + 0.15 * std::cos(a), 0.15 * std::sin(a));
  }
  const auto blobs = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking());
  ASSERT_EQ(blobs.size(), 3u);
  int boxes = 0;
  for (const auto& b : blobs) boxes += (b.centroid - Eigen::Vector2d(0.55, 0.0)).norm() < 0.02 ? 1 : 0;
  EXPECT_EQ(boxes, 1);
}

TEST(MovingObstacles, BlobMovingAtKnownVelocityGetsThatEstimate) {
  MovingObstacleTracker tracker(enabled_tracking());
  const Eigen::Vector2d v(-0.25, 0.1);
  for (int k = 0; k <= 30; ++k) {
    const double t = 0.1 * k;
    std::vector<Eigen::Vector2d> pts;
    add_square(pts, Eigen::Vector2d(2.0, -0.5) + v * t, 0.15, k);  // moving box
    add_square(pts, {-1.0, 1.0}, 0.3, k);                          // static post
    add_wall(pts, -3.0, 3.0, 2.5);
    tracker.update(pts, {0.0, 0.0}, t);
  }
  const Eigen::Vector2d at3 = Eigen::Vector2d(2.0, -0.5) + v * 3.0;
  const TrackedObstacle* box = track_near(tracker, at3);
  ASSERT_NE(box, nullptr);
  EXPECT_NEAR(box->velocity.x(), v.x(), 0.03);
  EXPECT_NEAR(box->velocity.y(), v.y(), 0.03);
  EXPECT_NEAR((box->predict(4.0) - (at3 + v)).norm(), 0.0, 0.05);
  const TrackedObstacle* post = track_near(tracker, {-1.0, 1.0});
  ASSERT_NE(post, nullptr);
  EXPECT_LT(post->velocity.norm(), 0.03);
  const auto moving = tracker.moving(3.0);
  ASSERT_EQ(moving.size(), 1u);
  EXPECT_EQ(moving[0].id, box->id);
  // Unseen tracks expire; a time that does not advance changes nothing.
  tracker.update({}, {0.0, 0.0}, 3.0);
  EXPECT_EQ(tracker.tracks().size(), 2u);
  tracker.update({}, {0.0, 0.0}, 4.0);
  EXPECT_TRUE(tracker.tracks().empty());
  EXPECT_TRUE(tracker.moving(4.0).empty());
}

TEST(MovingObstacles, BadParametersAreRejected) {
  MovingObstacleParams p;
  p.gate_m = -1.0;
  EXPECT_ANY_THROW(MovingObstacleTracker{p});
  DynamicAvoidanceParams a;
  a.horizon_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_ANY_THROW(a.validate());
  MovingObstacleParams m;
  m.global_map_margin_m = -0.1;
  EXPECT_ANY_THROW(m.validate());
  DynamicAvoidanceParams g;
  g.prediction_growth_mps = -0.05;
  EXPECT_ANY_THROW(g.validate());
  MovingObstacleParams s;
  s.structure_min_fraction = 0.0;
  EXPECT_ANY_THROW(s.validate());
  s.structure_min_fraction = 0.5;
  s.structure_age_s = -1.0;
  EXPECT_ANY_THROW(s.validate());
  MovingObstacleParams w;
  w.motion_window_s = 0.0;
  EXPECT_ANY_THROW(w.validate());
  w.motion_window_s = 4.0;
  w.moving_pause_s = -0.1;
  EXPECT_ANY_THROW(w.validate());
  MovingObstacleParams l;
  l.latch_displacement_m = -1.0;
  EXPECT_ANY_THROW(l.validate());
  l.latch_displacement_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_ANY_THROW(l.validate());
  DynamicAvoidanceParams h;
  h.hold_step_s = 0.25;
  EXPECT_NO_THROW(h.validate());
  h.hold_step_s = 0.5 * h.sim_step_s;  // finer than the rollout's steps
  EXPECT_ANY_THROW(h.validate());
  h.hold_step_s = -0.25;
  EXPECT_ANY_THROW(h.validate());
  h.hold_step_s = std::numeric_limits<double>::infinity();
  EXPECT_ANY_THROW(h.validate());
}

TEST(MovingObstacles, TimeToCollisionHeadOnAndPassingBehind) {
  TrackedObstacle o;
  o.position = {2.0, 0.0};
  o.velocity = {-0.25, 0.0};
  o.radius_m = 0.1;
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.2;
  p.safety_margin_m = 0.1;
  p.prediction_growth_mps = 0.0;
  p.horizon_s = 4.0;
  // Closing at 0.5 m/s from 2 m: within reach (0.4 m) after 3.2 s.
  EXPECT_NEAR(time_to_collision({0, 0, 0}, {0.25, 0, 0}, {o}, 0.0, p), 3.2, 0.11);
  // Standing still: 6.4 s, beyond the horizon.
  EXPECT_TRUE(std::isinf(time_to_collision({0, 0, 0}, {}, {o}, 0.0, p)));
  // Moving away from us: never.
  o.velocity = {0.25, 0.0};
  EXPECT_TRUE(std::isinf(time_to_collision({0, 0, 0}, {0.2, 0, 0}, {o}, 0.0, p)));
}

TEST(MovingObstacles, HeadOnPredictedCollisionMakesTheTrackerStopOrBackOff) {
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  const Path plan = test::straight_plan(0.0, 0.0, 3.5, 0.0);
  LocalPlannerParams params;
  params.avoidance.robot_radius_m = 0.3;
  // No moving obstacles: full speed ahead.
  auto free_tracker = make_local_planner("tracker", params);
  const Twist cruise{0.5, 0.0, 0.0};
  const auto r0 = free_tracker->compute({0, 0, 0}, cruise, plan, map, 2.0);
  ASSERT_TRUE(r0.result.ok());
  EXPECT_GT(r0.cmd.linear_x, 0.4);
  // A box 1.7 m ahead walking at us at 0.3 m/s (seen from t = 0 to 2 s).
  params.moving_obstacles = tracker_with({2.3, 0.0}, {-0.3, 0.0}, 2.0);
  ASSERT_EQ(params.moving_obstacles->moving(2.0).size(), 1u);
  for (const char* name : {"tracker", "teb"}) {
    SCOPED_TRACE(name);
    auto planner = make_local_planner(name, params);
    const auto r = planner->compute({0, 0, 0}, cruise, plan, map, 2.0);
    ASSERT_TRUE(r.result.ok()) << r.result.message;
    EXPECT_TRUE(planner->last_yield().modified);
    // Decelerating at the limit (0.5 m/s^2 over 0.1 s) towards a stop, a turn away or backing off.
    EXPECT_LT(r.cmd.linear_x, 0.5);
    EXPECT_LE(planner->last_yield().target.linear_x, 0.25);
    EXPECT_GT(planner->last_yield().ttc_s,
              time_to_collision({0, 0, 0}, cruise, params.moving_obstacles->moving(2.0), 2.0, params.avoidance));
  }
}

TEST(MovingObstacles, ObstacleThatPassesBeforeTheRobotArrivesChangesNothing) {
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  const Path plan = test::straight_plan(0.0, 0.0, 3.5, 0.0);
  LocalPlannerParams params;
  params.avoidance.robot_radius_m = 0.3;
  // Crossing 3 m ahead, already past the robot's lane, moving away from it.
  params.moving_obstacles = tracker_with({3.0, -1.0}, {0.0, -0.3}, 2.0);
  auto planner = make_local_planner("tracker", params);
  const auto r = planner->compute({0, 0, 0}, {0.5, 0.0, 0.0}, plan, map, 2.0);
  ASSERT_TRUE(r.result.ok());
  EXPECT_FALSE(planner->last_yield().modified);
  EXPECT_GT(r.cmd.linear_x, 0.4);
}

TEST(MovingObstacles, WhenEverythingCollidesTheCommandKeepingTheLargestGapWins) {
  // In a 0.9 m lane, a box already 0.5 m ahead and closing at 0.3 m/s: every candidate is within
  // reach at once; the yield must back off (the largest gap), not keep going or stop.
  auto map = test::empty_costmap(0.0, 0.0, 8.0);
  test::add_box(map, -3.0, 0.45, 3.0, 0.7);
  test::add_box(map, -3.0, -0.7, 3.0, -0.45);
  LocalPlannerParams params;
  params.avoidance.robot_radius_m = 0.3;
  const auto tracker = tracker_with({1.1, 0.0}, {-0.3, 0.0}, 2.0);
  const auto moving = tracker->moving(2.0);
  ASSERT_EQ(moving.size(), 1u);
  const CommandLimits lim{0.5, 0.25, 0.8, 0.5, 1.0};
  const auto y =
      yield_to_moving_obstacles({0.5, 0.0, 0.0}, {0, 0, 0}, {}, moving, map, lim, 0.1, 2.0, params.avoidance);
  ASSERT_TRUE(y.modified);
  EXPECT_LT(y.target.linear_x, 0.0) << y.target.linear_x << " " << y.target.angular_z;
  EXPECT_LT(y.cmd.linear_x, 0.0);
}

namespace {

// Where a command takes the robot from rest after t_s, within the acceleration limits (as the
// yield's rollouts: unicycle, velocity stepped towards the command every 0.1 s).
Pose2 roll_out(Pose2 pose, const Twist& target, const CommandLimits& lim, double t_s) {
  Twist v;
  for (double t = 0.0; t < t_s - 1e-9; t += 0.1) {
    v.linear_x += std::clamp(target.linear_x - v.linear_x, -0.1 * lim.acc_lim_x_mps2, 0.1 * lim.acc_lim_x_mps2);
    v.angular_z +=
        std::clamp(target.angular_z - v.angular_z, -0.1 * lim.acc_lim_theta_radps2, 0.1 * lim.acc_lim_theta_radps2);
    pose = pose * Pose2{0.1 * v.linear_x, 0.0, 0.1 * v.angular_z};
  }
  return pose;
}

}  // namespace

TEST(MovingObstacles, InAMoversLaneExitSweptCorridorLeavesTheLane) {
  // Digit (radius 0.35 m, Digit's limits) standing in a 0.5 m cube's lane (x = 0), turned 0.6 rad
  // towards it, the cube 0.9 m away coming down the lane at 0.25 m/s (three_rooms/digit, cube_2
  // just after the robot crossed ahead of it): every candidate is run into. The largest gap is
  // backing off down the lane ahead of the cube; leaving the corridor soonest is walking on
  // forward, turning away from the cube, out of the lane.
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  const CommandLimits lim{0.5, 0.25, 0.6, 0.5, 1.0};
  TrackedObstacle cube;
  cube.position = {0.0, 0.9};
  cube.velocity = {0.0, -0.25};
  cube.radius_m = 0.35;
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.35;
  // The corridor's half-width at the end of the horizon.
  const double reach = p.robot_radius_m + cube.radius_m + p.safety_margin_m + p.prediction_growth_mps * p.horizon_s;
  const Pose2 pose{0.0, 0.0, 0.6};
  const Twist cmd{0.1, 0.0, -0.3};
  ASSERT_FALSE(p.exit_swept_corridor);
  const auto gap = yield_to_moving_obstacles(cmd, pose, {}, {cube}, map, lim, 0.1, 0.0, p);
  ASSERT_TRUE(gap.modified);
  EXPECT_LT(gap.ttc_s, 0.5);  // nothing is free
  EXPECT_LT(gap.target.linear_x, 0.0);
  EXPECT_LT(std::abs(roll_out(pose, gap.target, lim, p.horizon_s).x), reach);
  p.exit_swept_corridor = true;
  const auto exit = yield_to_moving_obstacles(cmd, pose, {}, {cube}, map, lim, 0.1, 0.0, p);
  ASSERT_TRUE(exit.modified);
  EXPECT_LT(exit.ttc_s, 0.5);
  EXPECT_GT(exit.target.linear_x, 0.0);
  EXPECT_LT(exit.target.angular_z, 0.0);
  EXPECT_GT(roll_out(pose, exit.target, lim, p.horizon_s).x, reach);
}

TEST(MovingObstacles, ReverseAtStructureTurnsAMoverBackAtTheWall) {
  // A cube (radius 0.35 m) 0.8 m from a wall (lethal from y = -2.0 down) walks towards it at
  // 0.3 m/s; the robot (radius 0.38 m) crosses its lane 0.6 m in front of it at 0.3 m/s. Constant
  // velocity takes the cube through the wall and away from the robot's path: nothing to yield to.
  // Turned back where its leading edge reaches the wall (after ~1.6 s), it meets the robot in its
  // lane (three_rooms: cube_1 turns at the end of its lane as Digit crosses it).
  auto map = test::empty_costmap(0.0, 0.0, 8.0);
  test::add_box(map, -3.0, -2.2, 3.0, -2.0);
  TrackedObstacle cube;
  cube.id = 1;
  cube.position = {1.0, -1.2};
  cube.velocity = {0.0, -0.3};
  cube.radius_m = 0.35;
  const std::vector<TrackedObstacle> moving{cube};
  const CommandLimits lim{0.5, 0.25, 0.6, 0.5, 1.0};
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.38;
  const Pose2 pose{0.2, -0.6, 0.0};
  const Twist cmd{0.3, 0.0, 0.0};
  const auto straight = yield_to_moving_obstacles(cmd, pose, cmd, moving, map, lim, 0.1, 0.0, p);
  EXPECT_FALSE(straight.modified);
  EXPECT_FALSE(std::isfinite(straight.ttc_s));
  p.reverse_at_structure = true;
  const auto turned = yield_to_moving_obstacles(cmd, pose, cmd, moving, map, lim, 0.1, 0.0, p);
  EXPECT_TRUE(turned.modified);
  // Without a wall in its way the prediction is the straight one.
  const auto open =
      yield_to_moving_obstacles(cmd, pose, cmd, moving, test::empty_costmap(0.0, 0.0, 8.0), lim, 0.1, 0.0, p);
  EXPECT_FALSE(open.modified);
}

TEST(MovingObstacles, OfSeveralSafeCommandsTheClosestToThePlannersIsKept) {
  // A box crossing 1.2 m ahead from the right: slowing down or veering lets it pass; stopping
  // and backing off are safe too but further from the command.
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.2;
  const auto tracker = tracker_with({1.2, -1.6}, {0.0, 0.3}, 2.0);
  const auto moving = tracker->moving(2.0);
  ASSERT_EQ(moving.size(), 1u);
  const CommandLimits lim{0.5, 0.25, 0.8, 0.5, 1.0};
  const Twist cmd{0.5, 0.0, 0.0};
  const auto y = yield_to_moving_obstacles(cmd, {0, 0, 0}, cmd, moving, map, lim, 0.1, 2.0, p);
  ASSERT_TRUE(y.modified);
  EXPECT_TRUE(std::isinf(y.ttc_s));
  // Still moving forward (slower or veering away), neither stopping nor backing off.
  EXPECT_GT(y.target.linear_x, 0.0) << y.target.linear_x << " " << y.target.angular_z;
  EXPECT_FALSE(y.target.linear_x == cmd.linear_x && y.target.angular_z == cmd.angular_z);
}

TEST(MovingObstacles, BetweenTwoPostsInAMoversLaneHoldStepCandidatesStepAsideInsteadOfStanding) {
  // hexagon_dynamic/turtlebot3 seed 8 in miniature: the TurtleBot3 (radius 0.2 m, its limits)
  // stands in a box's lane (x = 0) between two posts (radius 0.15 m at x = +-0.4, 0.2 m inscribed
  // rings), facing one of them; the box comes down the lane at 0.25 m/s from 0.6 m. Every command
  // held for static_check_s (1.5 s) reaches a post's inscribed ring, so standing still was the
  // only candidate left; moving for a while and then braking is feasible and opens the gap.
  auto map = test::empty_costmap(0.0, 0.0, 8.0);
  test::add_disc(map, -0.4, 0.0, 0.15);
  test::add_disc(map, 0.4, 0.0, 0.15);
  const auto box_at = [](double y) {
    TrackedObstacle box;
    box.position = {0.0, y};
    box.velocity = {0.0, -0.25};
    box.radius_m = 0.1;
    return std::vector<TrackedObstacle>{box};
  };
  const auto moving = box_at(0.6);
  const CommandLimits lim{0.26, 0.26, 1.82, 2.5, 3.2};
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.2;
  const Twist cmd{0.26, 0.0, 0.0};
  ASSERT_EQ(p.hold_step_s, 0.0);
  const auto held = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, moving, map, lim, 0.1, 0.0, p);
  ASSERT_TRUE(held.modified);
  EXPECT_TRUE(held.target.is_zero()) << held.target.linear_x << " " << held.target.angular_z;
  p.hold_step_s = 0.25;
  const auto braked = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, moving, map, lim, 0.1, 0.0, p);
  ASSERT_TRUE(braked.modified);
  EXPECT_NE(braked.target.linear_x, 0.0) << braked.target.angular_z;
  EXPECT_NE(braked.cmd.linear_x, 0.0);
  EXPECT_TRUE(std::isfinite(braked.ttc_s));  // still run into: the lane is too narrow to clear it
  // In the open, with the box further up the lane, a held command is free, and the
  // held-then-braked ones are not considered.
  const auto open = test::empty_costmap(0.0, 0.0, 8.0);
  const auto far = box_at(1.2);
  p.hold_step_s = 0.0;
  const auto a = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, far, open, lim, 0.1, 0.0, p);
  p.hold_step_s = 0.25;
  const auto b = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, far, open, lim, 0.1, 0.0, p);
  EXPECT_FALSE(std::isfinite(a.ttc_s));
  EXPECT_EQ(a.target.linear_x, b.target.linear_x);
  EXPECT_EQ(a.target.angular_z, b.target.angular_z);
  EXPECT_EQ(a.ttc_s, b.ttc_s);
}

TEST(MovingObstacles, ClusterBlobsKeepTheHighestPointAndRejectMismatchedHeights) {
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {1.0, 1.0}, 0.15, 0);
  std::vector<double> heights(pts.size(), 0.2);
  heights[3] = 0.45;
  const auto blobs = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking(), heights);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_DOUBLE_EQ(blobs[0].top_m, 0.45);
  EXPECT_DOUBLE_EQ(cluster_blobs(pts, {0.0, 0.0}, enabled_tracking())[0].top_m, 0.0);
  heights.pop_back();
  EXPECT_THROW(cluster_blobs(pts, {0.0, 0.0}, enabled_tracking(), heights), Error);
}

TEST(MovingObstacles, VisibilityOfKnownPointsFromDigitsSensors) {
  const SensorVisibility vis = digit_visibility();
  // The LiDAR's lowest ring (-15 deg from 1.474 m) reaches a 0.5 m top at 0.974 / tan(15 deg) =
  // 3.635 m: beside the robot (outside both cameras) a 0.5 m cube is seen only beyond that.
  EXPECT_FALSE(vis.sees_base_point({0.0, 3.60, 0.5}));
  EXPECT_TRUE(vis.sees_base_point({0.0, 3.67, 0.5}));
  EXPECT_FALSE(vis.sees_base_point({0.0, 2.0, 0.5}));
  EXPECT_FALSE(vis.sees_base_point({0.0, -2.0, 0.3}));
  // Forward camera: 1.0 m ahead at 0.3 m is 35.8 deg below its horizon (axis at 45, half vfov 29).
  EXPECT_TRUE(vis.sees_base_point({1.0, 0.0, 0.3}));
  // 3 m ahead, 0.5 m high: 8.8 deg below the horizon (above the frustum) and 2.93 m from the
  // camera (beyond its 2.9 m range); too low for the LiDAR (-18 deg).
  EXPECT_FALSE(vis.sees_base_point({3.0, 0.0, 0.5}));
  // Backward camera, mirrored.
  EXPECT_TRUE(vis.sees_base_point({-1.2, 0.0, 0.3}));
  // Above the robot's head the LiDAR sees within +-15 deg only.
  EXPECT_TRUE(vis.sees_base_point({2.0, 0.0, 1.474}));
  EXPECT_FALSE(vis.sees_base_point({0.5, 0.0, 1.474 + 0.5}));
  // In the map frame: the robot at (10, 5) facing +y.
  const Pose2 robot{10.0, 5.0, 0.5 * M_PI};
  EXPECT_TRUE(vis.sees(robot, robot.transform({1.0, 0.0}), 0.5));
  EXPECT_FALSE(vis.sees(robot, robot.transform({0.0, 2.0}), 0.5));
  EXPECT_FALSE(vis.sees(robot, robot.transform({0.0, 3.6}), 0.5));
  EXPECT_TRUE(vis.sees(robot, robot.transform({0.0, 3.7}), 0.5));
  // A taller object beside the robot reaches the LiDAR's lowest ring closer: 1.0 m at 1.77 m.
  EXPECT_FALSE(vis.sees(robot, robot.transform({0.0, 1.74}), 1.0));
  EXPECT_TRUE(vis.sees(robot, robot.transform({0.0, 1.80}), 1.0));
  // No sensors: nothing is seen.
  EXPECT_FALSE(SensorVisibility().sees(robot, robot.transform({1.0, 0.0}), 0.5));
  SensorVisibilityParams bad;
  bad.depth_min_range_m = 5.0;
  EXPECT_THROW(SensorVisibility(digit_sensors(), bad), Error);
}

TEST(MovingObstacles, TrackCoastsThroughTheBlindZoneAndIsReassociated) {
  // A 0.5 m cube crosses 1 m in front of the robot from its left at 0.3 m/s; the sensors (the
  // visibility model) see it while the LiDAR does (beyond 3.635 m), lose it in the blind zone and
  // see it again once it enters the forward camera's frustum.
  MovingObstacleTracker tracker(coasting_tracking());
  tracker.set_visibility(digit_visibility());
  const Pose2 robot{0.0, 0.0, 0.0};
  const Eigen::Vector2d start(1.0, 4.8), v(0.0, -0.3);
  int id = 0;
  double blind_from = -1.0, blind_until = -1.0, last_seen = 0.0;
  for (int k = 0; k <= 150; ++k) {
    const double t = 0.1 * k;
    const Eigen::Vector2d c = start + v * t;
    const bool seen = tracker.visibility().sees(robot, c, 0.5);
    std::vector<Blob> blobs;
    if (seen) blobs.push_back(cube_blob(c));
    tracker.update_blobs(blobs, t, robot);
    if (!seen && blind_from < 0.0) blind_from = t;
    if (seen && blind_from >= 0.0 && blind_until < 0.0) blind_until = t;
    if (seen) last_seen = t;
    if (k == 20) {
      ASSERT_EQ(tracker.moving(t).size(), 1u);
      id = tracker.moving(t)[0].id;
    }
    if (blind_from >= 0.0 && blind_until < 0.0) {
      // Unseen in the blind zone: still the one moving track, coasting once older than
      // max_track_age_s, its radius grown by its uncertainty (bounded).
      const auto m = tracker.moving(t);
      ASSERT_EQ(m.size(), 1u) << t;
      EXPECT_EQ(m[0].id, id);
      EXPECT_EQ(m[0].coasting, t - last_seen > 0.6) << t;
      EXPECT_NEAR((m[0].position - c).norm(), 0.0, 0.05) << t;
      EXPECT_GE(m[0].radius_m, 0.35);
      EXPECT_LE(m[0].radius_m, 0.35 + 0.3 + 1e-12);
    }
    if (blind_until >= 0.0 && t - blind_until < 0.25) {
      const auto m = tracker.moving(t);
      ASSERT_EQ(m.size(), 1u) << t;
      EXPECT_EQ(m[0].id, id);  // re-associated, not a new track
      EXPECT_FALSE(m[0].coasting);
      EXPECT_DOUBLE_EQ(m[0].radius_m, 0.35);
    }
  }
  // The LiDAR loses it at y = sqrt(3.635^2 - 1) = 3.49 m (t = 4.4 s); the forward camera's frustum
  // (its right edge 42.5 deg off the axis) takes in its foot 0.05 m above the floor at
  // y = 0.916 * 0.707 * 1.8 = 1.166 m (t = 12.2 s). Before coasting it was dropped at 5.0 s.
  EXPECT_NEAR(blind_from, 4.4, 1e-9);
  EXPECT_NEAR(blind_until, 12.2, 1e-9);
}

TEST(MovingObstacles, UnseenTrackInViewIsDroppedAndCoastingIsBounded) {
  // Cycles every 0.125 s (exact in binary): a track unseen 0.5 s is kept, 0.625 s is too old.
  const Pose2 robot{0.0, 0.0, 0.0};
  const auto last_moving = [&](const MovingObstacleParams& params, const Eigen::Vector2d& start,
                               const Eigen::Vector2d& v, double until_s, bool with_pose) {
    MovingObstacleTracker tracker(params);
    tracker.set_visibility(digit_visibility());
    double last = -1.0;
    for (int k = 0; 0.125 * k <= until_s; ++k) {
      const double t = 0.125 * k;
      std::vector<Blob> blobs;
      if (t <= 2.0) blobs.push_back(cube_blob(start + v * t));  // seen for 2 s, then never again
      if (with_pose)
        tracker.update_blobs(blobs, t, robot);
      else
        tracker.update_blobs(blobs, t);
      if (!tracker.moving(t).empty()) last = t;
    }
    return last;
  };
  const MovingObstacleParams p = coasting_tracking();
  // In front of the robot, in the forward camera's view: dropped once unseen longer than
  // max_track_age_s, as without coasting.
  EXPECT_DOUBLE_EQ(last_moving(p, {1.0, 0.6}, {0.0, -0.2}, 6.0, true), 2.5);
  // 2 m beside the robot (below the LiDAR's lowest ring, outside both cameras) it coasts for
  // max_coast_s (10 s).
  EXPECT_DOUBLE_EQ(last_moving(p, {0.2, 2.0}, {0.2, 0.0}, 14.0, true), 12.0);
  MovingObstacleParams shorter = p;
  shorter.max_coast_s = 3.0;
  EXPECT_DOUBLE_EQ(last_moving(shorter, {0.2, 2.0}, {0.2, 0.0}, 14.0, true), 5.0);
  // Moving away beside the robot, its prediction enters the LiDAR's view (3.635 m) at
  // x = 2.540 m, t = 2 + (2.540 - 1.9) / 0.2 = 5.20 s: there the sensors' silence counts and it goes.
  EXPECT_DOUBLE_EQ(last_moving(p, {1.5, -2.6}, {0.2, 0.0}, 14.0, true), 5.125);
  // Without the robot's pose (the 2D update) there is no coasting; nor when it is switched off.
  EXPECT_DOUBLE_EQ(last_moving(p, {0.2, 2.0}, {0.2, 0.0}, 14.0, false), 2.5);
  MovingObstacleParams off = p;
  off.coast_in_blind_zone = false;
  EXPECT_DOUBLE_EQ(last_moving(off, {0.2, 2.0}, {0.2, 0.0}, 14.0, true), 2.5);
}

TEST(MovingObstacles, KeepLargestRadiusRemembersTheWholeObject) {
  // A 0.5 m cube (bounding radius 0.35 m) seen whole, then only a corner of it (radius 0.1 m) as it
  // crosses the edge of the sensors' view: with keep_largest_radius the track keeps 0.35 m.
  const auto radius_after = [](bool keep) {
    MovingObstacleParams p;
    p.keep_largest_radius = keep;
    MovingObstacleTracker tracker(p);
    for (int k = 0; k <= 20; ++k) {
      const double t = 0.1 * k;
      const Eigen::Vector2d c(0.3 * t, 2.0);
      tracker.update_blobs({Blob{c, k < 10 ? 0.35 : 0.1, 0.5, 20}}, t);
    }
    const auto m = tracker.moving(2.0);
    return m.size() == 1 ? m[0].radius_m : -1.0;
  };
  EXPECT_DOUBLE_EQ(radius_after(false), 0.1);
  EXPECT_DOUBLE_EQ(radius_after(true), 0.35);
}

TEST(MovingObstacles, RadiusFloorKeepsTheRadiusOfAShrinkingBlob) {
  // A 0.5 m cube (bounding radius 0.35 m) moving at 0.3 m/s, seen whole for 1 s, then shrinking to
  // 0.06 m over 1 s as it passes under the LiDAR's lowest ring: with radius_floor the track keeps
  // 0.35 m (the largest of the last 5 s), without it follows the blob.
  const auto radius_after = [](bool floor, double window_s) {
    MovingObstacleParams p;
    p.radius_floor = floor;
    p.radius_floor_window_s = window_s;
    MovingObstacleTracker tracker(p);
    for (int k = 0; k <= 20; ++k) {
      const double t = 0.1 * k;
      const double r = k <= 10 ? 0.35 : 0.35 - 0.029 * (k - 10);
      tracker.update_blobs({Blob{Eigen::Vector2d(0.3 * t, 2.0), r, 0.5, 20}}, t);
    }
    const auto m = tracker.moving(2.0);
    return m.size() == 1 ? m[0].radius_m : -1.0;
  };
  EXPECT_NEAR(radius_after(false, 5.0), 0.06, 1e-9);
  EXPECT_DOUBLE_EQ(radius_after(true, 5.0), 0.35);
  // The floor is the largest of the window only: 0.5 s back the blob was 0.205 m.
  EXPECT_NEAR(radius_after(true, 0.5), 0.205, 1e-9);
}

TEST(MovingObstacles, RadiusFloorContinuesALostTrackFoundAgain) {
  // A cube moving at 0.3 m/s in +x is seen whole for 2 s, unseen for 1.5 s (dropped after 0.6 s:
  // no coasting without the robot's pose), then seen again 0.3 m from its prediction as a partial
  // view (0.03 m). With radius_floor the new blob continues the lost track: same id, confirmed and
  // moving at once, with the whole cube's radius; without it, a new unconfirmed track.
  const auto after = [](bool floor) {
    MovingObstacleParams p;
    p.radius_floor = floor;
    MovingObstacleTracker tracker(p);
    for (int k = 0; k <= 20; ++k) {
      const double t = 0.1 * k;
      tracker.update_blobs({Blob{Eigen::Vector2d(0.3 * t, 2.0), 0.35, 0.5, 20}}, t);
    }
    for (int k = 21; k < 35; ++k) tracker.update_blobs({}, 0.1 * k);
    tracker.update_blobs({Blob{Eigen::Vector2d(0.3 * 3.5, 2.3), 0.03, 0.5, 5}}, 3.5);
    return tracker.moving(3.5);
  };
  const auto off = after(false), on = after(true);
  EXPECT_TRUE(off.empty());
  ASSERT_EQ(on.size(), 1u);
  EXPECT_EQ(on[0].id, 1);
  EXPECT_DOUBLE_EQ(on[0].radius_m, 0.35);
  EXPECT_NEAR(on[0].velocity.x(), 0.3, 0.05);
}

TEST(MovingObstacles, ReacquireCoastingContinuesACoastingTrackFoundFarFromItsPrediction) {
  // A cube 2.5 m beside the robot (below the LiDAR's lowest ring, outside both cameras) moves at
  // 0.5 m/s in +x, seen for 2 s, then turns back unseen: its track coasts on in +x. At 3.4 s it is
  // seen again at x = 0.5, 1.4 m from the prediction (x = 1.9), beyond gate_m plus the coasting
  // growth (0.75 m) but within reacquire_gate_m of the segment from where it was last seen
  // (x = 1.2). With reacquire_coasting the blob continues the coasting track (same id, moving at
  // once, at the blob); without it a new unconfirmed track starts and the stale prediction stays.
  const Pose2 robot{0.0, 0.0, 0.0};
  const auto cube_x = [](double t) { return t <= 2.0 ? 0.2 + 0.5 * t : 1.2 - 0.5 * (t - 2.0); };
  const auto run = [&](bool reacquire, double until_s) {
    MovingObstacleParams p = coasting_tracking();
    p.radius_floor = true;
    p.reacquire_coasting = reacquire;
    MovingObstacleTracker tracker(p);
    tracker.set_visibility(digit_visibility());
    for (int k = 0; 0.1 * k <= until_s + 1e-9; ++k) {
      const double t = 0.1 * k;
      std::vector<Blob> blobs;
      if (t <= 2.0 + 1e-9 || t >= 3.4 - 1e-9) blobs.push_back(cube_blob({cube_x(t), 2.5}));
      tracker.update_blobs(blobs, t, robot);
    }
    return tracker;
  };
  const double t_seen = 3.4;
  const auto on = run(true, t_seen), off = run(false, t_seen);
  const auto m_on = on.moving(t_seen), m_off = off.moving(t_seen);
  ASSERT_EQ(m_on.size(), 1u);
  EXPECT_EQ(m_on[0].id, 1);
  EXPECT_FALSE(m_on[0].coasting);
  EXPECT_NEAR(m_on[0].position.x(), cube_x(t_seen), 1e-9);
  EXPECT_DOUBLE_EQ(m_on[0].radius_m, 0.35);
  EXPECT_EQ(on.tracks().size(), 1u);  // no stale coasting copy left behind
  ASSERT_EQ(m_off.size(), 1u);
  EXPECT_EQ(m_off[0].id, 1);
  EXPECT_TRUE(m_off[0].coasting);
  EXPECT_GT(std::abs(m_off[0].position.x() - cube_x(t_seen)), 1.3);
  EXPECT_EQ(off.tracks().size(), 2u);
  // Its velocity follows the blobs from there on (a new track's variance): -0.5 m/s after 1 s.
  const auto later = run(true, t_seen + 1.0);
  ASSERT_EQ(later.tracks().size(), 1u);
  EXPECT_EQ(later.tracks()[0].id, 1);
  EXPECT_NEAR(later.tracks()[0].velocity.x(), -0.5, 0.05);
}

TEST(MovingObstacles, PartialViewNoiseKeepsTheVelocityOfAShrinkingBlob) {
  // A 0.5 m cube moving at 0.25 m/s in -y, seen whole for 3 s; then, for 0.6 s, only a shrinking
  // piece of its far side (as it passes under the LiDAR's lowest ring), whose centroid recedes
  // from the robot (+x) by up to 0.25 m.
  const auto velocity_after = [](bool partial_view_noise) {
    MovingObstacleParams p;
    p.partial_view_noise = partial_view_noise;
    MovingObstacleTracker tracker(p);
    for (int k = 0; k <= 36; ++k) {
      const double t = 0.1 * k;
      const Eigen::Vector2d c(0.0, 2.0 - 0.25 * t);
      const double f = k <= 30 ? 0.0 : (k - 30) / 6.0;  // share of the view lost
      tracker.update_blobs({Blob{c + Eigen::Vector2d(0.25 * f, 0.0), 0.35 - 0.3 * f, 0.5, 20}}, t);
    }
    EXPECT_EQ(tracker.tracks().size(), 1u);
    return tracker.tracks().empty() ? Eigen::Vector2d::Zero().eval() : tracker.tracks()[0].velocity;
  };
  const Eigen::Vector2d off = velocity_after(false), on = velocity_after(true);
  // The receding centroid is read as motion away (0.415 m/s), with the noise grown by the lost
  // extent less than half of it (0.169 m/s); the true motion is kept either way.
  EXPECT_GT(off.x(), 0.4);
  EXPECT_LT(on.x(), 0.2);
  EXPECT_NEAR(off.y(), -0.25, 0.01);
  EXPECT_NEAR(on.y(), -0.25, 0.01);
}

}  // namespace bipednav::planning::local

namespace bipednav::planning::local {

namespace {

// An occupancy grid (0.1 m cells, 12 m square around the origin) with a wall's cells lethal along
// y = wall_y from x = -3 to 6 and, when `cube` is given, the cells of a 0.5 m cube centred there
// (the global map keeps a mover's cells lethal while it is on them).
mapping::Costmap2D occupancy_with_wall(double wall_y, const std::optional<Eigen::Vector2d>& cube = std::nullopt) {
  mapping::Costmap2D m = test::empty_costmap(0.0, 0.0, 12.0, 0.1);
  const auto mark = [&](double x, double y) {
    if (const auto c = m.geometry().world_to_cell(x, y)) m.set_cost(*c, mapping::kLethal);
  };
  for (double x = -3.0; x <= 6.0; x += 0.05) mark(x, wall_y);
  if (cube) {
    for (double dx = -0.25; dx <= 0.25 + 1e-9; dx += 0.05)
      for (double dy = -0.25; dy <= 0.25 + 1e-9; dy += 0.05) mark(cube->x() + dx, cube->y() + dy);
  }
  return m;
}

// The piece of the wall along y = wall_y that a sensor sees at time t: 0.6 m of it, its start
// sliding along the wall at 1 m/s (the edge of a depth camera's view as the robot turns, or the
// gap between sparse returns at grazing incidence as it walks).
void add_wall_piece(std::vector<Eigen::Vector2d>& pts, double wall_y, double t) {
  const double a = 0.5 + 1.0 * t;
  add_wall(pts, a, a + 0.6, wall_y);
}

}  // namespace

TEST(MovingObstacles, StaticStructureIsLethalCellsOfAGivenAge) {
  mapping::Costmap2D m = test::empty_costmap(0.0, 0.0, 4.0, 0.1);
  const auto cell = *m.geometry().world_to_cell(1.0, 1.0);
  const Eigen::Vector2d at(1.05, 1.05), beside(1.25, 1.05);
  StaticStructure s;
  EXPECT_TRUE(s.empty());
  EXPECT_FALSE(s.near(at, 0.2, 0.0));
  m.set_cost(cell, mapping::kLethal);
  s.update(m, 0.0);
  EXPECT_TRUE(s.near(at, 0.0, 0.0));
  EXPECT_FALSE(s.near(at, 0.0, 4.0));  // not old enough yet
  s.update(m, 3.9);
  EXPECT_FALSE(s.near(at, 0.0, 4.0));
  s.update(m, 4.0);
  EXPECT_TRUE(s.near(at, 0.0, 4.0));
  EXPECT_TRUE(s.near(beside, 0.2, 4.0));  // within the margin
  EXPECT_FALSE(s.near(beside, 0.1, 4.0));
  s.update(m, 3.0);  // a time that does not advance changes nothing
  EXPECT_TRUE(s.near(at, 0.0, 4.0));
  m.set_cost(cell, mapping::kFree);  // cleared: its age starts over when it is marked again
  s.update(m, 5.0);
  EXPECT_FALSE(s.near(at, 0.0, 0.0));
  m.set_cost(cell, mapping::kLethal);
  s.update(m, 6.0);
  s.update(m, 9.9);
  EXPECT_FALSE(s.near(at, 0.0, 4.0));
  s.update(m, 10.0);
  EXPECT_TRUE(s.near(at, 0.0, 4.0));
}

TEST(MovingObstacles, SlidingPieceOfAWallIsNoMover) {
  // The robot walks along a wall 1 m to its left while the piece of it that it sees slides along
  // the wall: without the map that piece becomes a track moving at about 1 m/s.
  const double wall_y = 1.0;
  const mapping::Costmap2D occupancy = occupancy_with_wall(wall_y);
  MovingObstacleParams on = enabled_tracking();
  on.ignore_static_structure = true;
  MovingObstacleTracker blind(enabled_tracking()), mapped(on);
  mapped.set_static_structure(occupancy, -5.0);  // the wall has been in the map for a while
  bool blind_moving = false;
  for (int k = 0; k <= 30; ++k) {
    const double t = 0.1 * k;
    std::vector<Eigen::Vector2d> pts;
    add_wall_piece(pts, wall_y, t);
    const Pose2 robot{0.4 * t, 0.0, 0.3 * t};
    blind.update(pts, std::vector<double>(pts.size(), 2.0), robot, t);
    mapped.set_static_structure(occupancy, t);
    mapped.update(pts, std::vector<double>(pts.size(), 2.0), robot, t);
    for (const auto& m : blind.moving(t)) blind_moving = blind_moving || m.velocity.x() > 0.5;
    EXPECT_TRUE(mapped.moving(t).empty()) << "t = " << t;
  }
  EXPECT_TRUE(blind_moving);
  EXPECT_TRUE(mapped.tracks().empty());
  // Switched off (the default), the map changes nothing.
  MovingObstacleTracker unused(enabled_tracking());
  unused.set_static_structure(occupancy, -5.0);
  EXPECT_TRUE(unused.static_structure().empty());
}

TEST(MovingObstacles, CubeBesideAWallIsStillTracked) {
  // A 0.5 m cube moving at 0.3 m/s along the wall, 0.35 m from it, while the robot walks and
  // sees a sliding piece of the wall: the cube is the one moving track.
  const double wall_y = 1.0;
  const Eigen::Vector2d v(0.3, 0.0);
  MovingObstacleParams on = enabled_tracking();
  on.ignore_static_structure = true;
  MovingObstacleTracker tracker(on);
  tracker.set_static_structure(occupancy_with_wall(wall_y), -5.0);
  Eigen::Vector2d cube(-0.5, wall_y - 0.35 - 0.25);
  for (int k = 0; k <= 40; ++k) {
    const double t = 0.1 * k;
    cube = Eigen::Vector2d(-0.5, wall_y - 0.6) + v * t;
    std::vector<Eigen::Vector2d> pts;
    add_wall_piece(pts, wall_y, t);
    add_square(pts, cube, 0.5, k);
    const Pose2 robot{0.4 * t, 0.0, 0.0};
    tracker.set_static_structure(occupancy_with_wall(wall_y, cube), t);  // the map has the cube where it is
    tracker.update(pts, std::vector<double>(pts.size(), 0.5), robot, t);
  }
  const auto moving = tracker.moving(4.0);
  ASSERT_EQ(moving.size(), 1u);
  EXPECT_LT((moving[0].position - cube).norm(), 0.05);
  EXPECT_NEAR(moving[0].velocity.x(), v.x(), 0.05);
  EXPECT_NEAR(moving[0].velocity.y(), v.y(), 0.05);
}

TEST(MovingObstacles, WalkerGoingToAndFroStaysMovingThroughItsTurnarounds) {
  // Someone walking to and fro between y = -1.5 and 1.5, first seen at y = 0, at the slowest
  // speed of the scenarios' movers (0.25 m/s) and at the person's (0.4 m/s): over 40 s they turn
  // round several times and pass where their track began, and stay the one moving track.
  MovingObstacleParams recent = enabled_tracking();
  recent.recent_motion = true;
  for (const double speed : {0.25, 0.4}) {
    MovingObstacleTracker tracker(recent), from_origin(enabled_tracking());
    double first_moving_s = -1.0;
    int id = -1;
    bool lost_from_origin = false;  // the distance from the first centroid loses them
    for (int k = 0; k <= 400; ++k) {
      const double t = 0.1 * k;
      const double u = std::fmod(speed * t + 1.5, 6.0);  // distance along one lap, up then down
      const double y = u < 3.0 ? u - 1.5 : 4.5 - u;
      std::vector<Eigen::Vector2d> pts;
      add_square(pts, {1.0, y}, 0.4, k);
      tracker.update(pts, {0.0, 0.0}, t);
      from_origin.update(pts, {0.0, 0.0}, t);
      const auto moving = tracker.moving(t);
      if (first_moving_s >= 0.0) lost_from_origin = lost_from_origin || from_origin.moving(t).empty();
      if (first_moving_s < 0.0) {
        if (!moving.empty()) first_moving_s = t, id = moving[0].id;
        continue;
      }
      ASSERT_EQ(moving.size(), 1u) << speed << " m/s at t = " << t << " s, y = " << y;
      EXPECT_EQ(moving[0].id, id);
      EXPECT_LT((moving[0].position - Eigen::Vector2d(1.0, y)).norm(), 0.15) << speed << " m/s at t = " << t;
    }
    EXPECT_GT(first_moving_s, 0.0) << speed;
    EXPECT_LT(first_moving_s, 0.3 / speed + 0.5) << speed;
    EXPECT_TRUE(lost_from_origin) << speed;
  }
}

TEST(MovingObstacles, StaticBoxSeenFromAPassingRobotNeverMoves) {
  // A 0.4 m box at the origin seen from a robot passing 1 m in front of it at 0.4 m/s, and a 0.2 m
  // post beside its path: the faces seen of the box turn from left and front to front to front and
  // right (its blob's centroid slides 0.2 m), points drop out and jitter by up to 2 cm, and the
  // post's centroid jitters by up to 4 cm (partial segmentation).
  MovingObstacleParams recent = enabled_tracking();
  recent.recent_motion = true;
  MovingObstacleTracker tracker(recent), from_origin(enabled_tracking());
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
    from_origin.update(pts, robot, t);
    EXPECT_TRUE(tracker.moving(t).empty()) << "t = " << t;
    EXPECT_TRUE(from_origin.moving(t).empty()) << "t = " << t;
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

namespace {

std::uint64_t reference_cell_key(long x, long y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(y));
}

// cluster_blobs before its binning ran four points at a time (AVX2) into kept buffers: the
// bitwise reference of ClusterBlobsBinningMatchesTheScalarCode.
std::vector<Blob> cluster_blobs_scalar_binning(const std::vector<Eigen::Vector2d>& points,
                                               const Eigen::Vector2d& center, const MovingObstacleParams& params,
                                               const std::vector<double>& heights, const StaticStructure* structure) {
  const bool check_structure = params.ignore_static_structure && structure != nullptr && !structure->empty();
  require(heights.empty() || heights.size() == points.size(), "cluster_blobs heights",
          "empty or one per point (" + std::to_string(points.size()) + "), got " + std::to_string(heights.size()));
  std::vector<Blob> out;
  const double cell = params.cluster_cell_m;
  const double r2max = params.max_range_m * params.max_range_m;
  // The bins of the points in range, in point order.
  std::vector<long> bx, by;
  std::vector<std::size_t> in_range;
  bx.reserve(points.size());
  by.reserve(points.size());
  in_range.reserve(points.size());
  long x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    if (!p.allFinite() || (p - center).squaredNorm() > r2max) continue;
    const auto x = static_cast<long>(std::floor(p.x() / cell)), y = static_cast<long>(std::floor(p.y() / cell));
    if (in_range.empty()) x_lo = x_hi = x, y_lo = y_hi = y;
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    bx.push_back(x);
    by.push_back(y);
    in_range.push_back(i);
  }
  if (in_range.empty()) return out;
  // Cells in a fixed order, (x, y) ascending, each a [begin, end) range of `order` (point indices,
  // ascending within a cell). The bins span a small window (max_range_m around the robot): a
  // counting sort over it; a hash of the bins when the window is too large for that.
  std::vector<std::size_t> order(in_range.size());
  std::vector<std::pair<std::size_t, std::size_t>> cells;
  std::vector<std::pair<long, long>> cell_xy;
  const auto span_x = static_cast<unsigned long>(x_hi - x_lo), span_y = static_cast<unsigned long>(y_hi - y_lo);
  const std::size_t grid_limit = std::max<std::size_t>(1 << 16, 8 * in_range.size());
  const bool dense = span_x < grid_limit && span_y < grid_limit && (span_x + 1) * (span_y + 1) <= grid_limit;
  const auto H = static_cast<std::size_t>(span_y + 1);
  std::vector<std::int32_t> grid;  // dense: cell index per bin, -1 when empty
  std::unordered_map<std::uint64_t, std::size_t> cell_of;
  if (dense) {
    const std::size_t W = static_cast<std::size_t>(span_x + 1);
    std::vector<std::uint32_t> start(W * H + 1, 0);
    const auto bin = [&](std::size_t k) {
      return static_cast<std::size_t>(bx[k] - x_lo) * H + static_cast<std::size_t>(by[k] - y_lo);
    };
    for (std::size_t k = 0; k < in_range.size(); ++k) ++start[bin(k) + 1];
    grid.assign(W * H, -1);
    for (std::size_t b = 0; b < W * H; ++b) {
      if (start[b + 1] > 0) {
        grid[b] = static_cast<std::int32_t>(cells.size());
        cells.emplace_back(start[b], start[b] + start[b + 1]);
        cell_xy.emplace_back(x_lo + static_cast<long>(b / H), y_lo + static_cast<long>(b % H));
      }
      start[b + 1] += start[b];
    }
    for (std::size_t k = 0; k < in_range.size(); ++k) order[start[bin(k)]++] = in_range[k];
  } else {
    std::vector<std::tuple<long, long, std::size_t>> binned(in_range.size());
    for (std::size_t k = 0; k < in_range.size(); ++k) binned[k] = {bx[k], by[k], in_range[k]};
    std::sort(binned.begin(), binned.end());
    for (std::size_t i = 0; i < binned.size();) {
      std::size_t j = i;
      while (j < binned.size() && std::get<0>(binned[j]) == std::get<0>(binned[i]) &&
             std::get<1>(binned[j]) == std::get<1>(binned[i]))
        ++j;
      cell_of.emplace(reference_cell_key(std::get<0>(binned[i]), std::get<1>(binned[i])), cells.size());
      cells.emplace_back(i, j);
      cell_xy.emplace_back(std::get<0>(binned[i]), std::get<1>(binned[i]));
      i = j;
    }
    for (std::size_t k = 0; k < binned.size(); ++k) order[k] = std::get<2>(binned[k]);
  }
  // The cell at bin (x, y), or -1.
  const auto find_cell = [&](long x, long y) -> std::int64_t {
    if (dense) {
      if (x < x_lo || x > x_hi || y < y_lo || y > y_hi) return -1;
      return grid[static_cast<std::size_t>(x - x_lo) * H + static_cast<std::size_t>(y - y_lo)];
    }
    const auto it = cell_of.find(reference_cell_key(x, y));
    return it == cell_of.end() ? -1 : static_cast<std::int64_t>(it->second);
  };
  std::vector<char> seen(cells.size(), 0);
  std::vector<std::size_t> stack, members;
  for (std::size_t c0 = 0; c0 < cells.size(); ++c0) {
    if (seen[c0]) continue;
    seen[c0] = 1;
    stack.assign(1, c0);
    members.clear();
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      members.push_back(c);
      const auto [cx, cy] = cell_xy[c];
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dx = -1; dx <= 1; ++dx) {
          const std::int64_t n = find_cell(cx + dx, cy + dy);
          if (n >= 0 && !seen[static_cast<std::size_t>(n)])
            seen[static_cast<std::size_t>(n)] = 1, stack.push_back(static_cast<std::size_t>(n));
        }
      }
    }
    Blob b;
    for (const std::size_t c : members) {
      for (std::size_t k = cells[c].first; k < cells[c].second; ++k) {
        const std::size_t i = order[k];
        b.centroid += points[i];
        if (!heights.empty() && std::isfinite(heights[i])) b.top_m = std::max(b.top_m, heights[i]);
      }
      b.points += static_cast<int>(cells[c].second - cells[c].first);
    }
    b.centroid /= static_cast<double>(b.points);
    // The largest distance is the square root of the largest squared distance (the rounded square
    // root is monotonic): one square root per blob.
    double r2 = 0.0;
    for (const std::size_t c : members) {
      for (std::size_t k = cells[c].first; k < cells[c].second; ++k)
        r2 = std::max(r2, (points[order[k]] - b.centroid).squaredNorm());
    }
    b.radius_m = std::max(b.radius_m, std::sqrt(r2));
    if (b.points < params.min_points || b.radius_m > params.max_blob_radius_m) continue;
    if (check_structure) {
      // The share of the blob's binning cells (at their centres) on long-standing structure.
      std::size_t on = 0;
      for (const std::size_t c : members) {
        const Eigen::Vector2d q((static_cast<double>(cell_xy[c].first) + 0.5) * cell,
                                (static_cast<double>(cell_xy[c].second) + 0.5) * cell);
        if (structure->near(q, params.structure_margin_m, params.structure_age_s)) ++on;
      }
      if (static_cast<double>(on) >= params.structure_min_fraction * static_cast<double>(members.size())) continue;
    }
    out.push_back(b);
  }
  return out;
}

}  // namespace

// The AVX2 binning (finite test, range test, quotient, floor) gives the scalar code's bins, so the
// same blobs bit for bit: points on cell borders and on the range circle, non-finite points,
// coordinates beyond int32 bins (the scalar fallback, and the sorted bins), every length mod 4, runs
// of points in one bin.
TEST(MovingObstacles, ClusterBlobsBinningMatchesTheScalarCode) {
  std::uint64_t state = 12345;
  const auto uniform = [&] {  // splitmix64 in [0, 1)
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  MovingObstacleParams params = enabled_tracking();
  params.min_points = 1;
  params.max_blob_radius_m = 1e300;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector2d center(4.0 * uniform() - 2.0, 4.0 * uniform() - 2.0);
    std::vector<Eigen::Vector2d> pts;
    std::vector<double> heights;
    const int n = trial % 37 + static_cast<int>(400 * uniform());
    for (int i = 0; i < n; ++i) {
      const double kind = uniform();
      Eigen::Vector2d p(center.x() + 12.0 * uniform() - 6.0, center.y() + 12.0 * uniform() - 6.0);
      if (kind < 0.1) {  // on a cell border
        p = Eigen::Vector2d(std::round(p.x() * 10.0) * 0.1, std::round(p.y() * 10.0) / 10.0);
      } else if (kind < 0.15) {  // on (or next to) the range circle
        const double a = 6.283185307179586 * uniform();
        p = center + params.max_range_m * Eigen::Vector2d(std::cos(a), std::sin(a));
      } else if (kind < 0.18) {
        p = Eigen::Vector2d(uniform() < 0.5 ? nan : inf, p.y());
      } else if (kind < 0.2) {
        p = Eigen::Vector2d(p.x(), uniform() < 0.5 ? -inf : nan);
      } else if (kind < 0.6 && !pts.empty()) {  // runs of points in one bin (or the next)
        p = pts.back() + Eigen::Vector2d(0.02 * uniform() - 0.01, 0.02 * uniform() - 0.01);
      }
      pts.push_back(p);
      heights.push_back(uniform() < 0.05 ? nan : uniform());
    }
    MovingObstacleParams q = params;
    if (trial % 5 == 4) q.max_range_m = 1e12;  // bins beyond int32 (and a window too large for the grid)
    if (trial % 5 == 4)
      for (int i = 0; i < n; i += 7) pts[static_cast<std::size_t>(i)] *= 1e10;
    const auto got = cluster_blobs(pts, center, q, trial % 2 ? heights : std::vector<double>{});
    const auto want =
        cluster_blobs_scalar_binning(pts, center, q, trial % 2 ? heights : std::vector<double>{}, nullptr);
    ASSERT_EQ(got.size(), want.size()) << "trial " << trial;
    for (std::size_t b = 0; b < got.size(); ++b) {
      EXPECT_EQ(got[b].points, want[b].points);
      EXPECT_EQ(std::memcmp(&got[b].centroid, &want[b].centroid, sizeof(Eigen::Vector2d)), 0) << "trial " << trial;
      EXPECT_EQ(std::memcmp(&got[b].radius_m, &want[b].radius_m, sizeof(double)), 0);
      EXPECT_EQ(std::memcmp(&got[b].top_m, &want[b].top_m, sizeof(double)), 0);
    }
  }
}

}  // namespace bipednav::planning::local
