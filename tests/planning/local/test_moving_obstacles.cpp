#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

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

}  // namespace bipednav::planning::local
