#include "bipednav/planning/local/moving_obstacles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "bipednav/planning/local/moving_obstacle_yield.hpp"
#include "moving_obstacle_test_utils.hpp"

namespace bipednav::planning::local {

namespace {

const TrackedObstacle* track_near(const MovingObstacleTracker& t, const Eigen::Vector2d& p) {
  for (const auto& tr : t.tracks())
    if ((tr.position - p).norm() < 0.2) return &tr;
  return nullptr;
}

MovingObstacleParams coasting_tracking() {
  MovingObstacleParams p = enabled_tracking();
  p.coast_in_blind_zone = true;
  return p;
}

// The blob of a 0.5 m cube centred at c (the outline a sensor sees of it).
Blob cube_blob(const Eigen::Vector2d& c) { return Blob{c, 0.35, 0.5, 40}; }

}  // namespace

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

TEST(MovingObstacles, ATrackPassedToTheNextPostIsNoMoverWhileItsFirstPostIsThere) {
  // Two posts 0.3 m apart, seen as one blob for half a second (their points bridged, as 0.1 m bins
  // join them): the first post's track is pulled towards the second, gains speed and is passed on
  // to it. It is 0.3 m from its origin, fast, but the first post still stands there. The box that
  // starts beside the posts leaves where it was. Had the first post gone from view once the blobs
  // parted, the passed-on track would have been a mover.
  const auto moving_ids = [](bool first_post_stays) {
    MovingObstacleTracker tracker(enabled_tracking());
    std::vector<int> ids;
    int box = -1;
    for (int k = 0; k <= 25; ++k) {
      const double t = 0.1 * k;
      std::vector<Eigen::Vector2d> pts;
      if (first_post_stays || k < 15) add_square(pts, {1.0, 2.0}, 0.1, k);
      if (k >= 10) add_square(pts, {1.3, 2.0}, 0.1, k);
      if (k >= 10 && k < 15)
        for (double x = 1.06; x < 1.25; x += 0.02) pts.emplace_back(x, 2.0);
      const Eigen::Vector2d box_at(-1.0 + 0.4 * t, -1.0);
      add_square(pts, box_at, 0.2, k);
      tracker.update(pts, {0.0, 0.0}, t);
      if (const TrackedObstacle* b = track_near(tracker, box_at)) box = b->id;
      for (const auto& m : tracker.moving(t))
        if (m.id != box && std::find(ids.begin(), ids.end(), m.id) == ids.end()) ids.push_back(m.id);
    }
    return std::make_pair(ids, tracker.moving(2.5).size());
  };
  const auto [ids, moving] = moving_ids(true);
  EXPECT_TRUE(ids.empty());
  EXPECT_EQ(moving, 1u);  // the box
  EXPECT_FALSE(moving_ids(false).first.empty());
}

TEST(MovingObstacles, APacerIsPredictedToTurnWhereItTurnedBefore) {
  // A box pacing at 0.8 m/s between x = 0 and x = 2 (y = 1), turning on the spot at the ends,
  // seen at 10 Hz for two laps and a bit: at x = 1.6 heading +x it turns in 0.5 s, so 1 s ahead it
  // is back at x = 1.6, where the constant velocity puts it at 2.4.
  const double speed = 0.8, lap_s = 2.0 * 2.0 / speed;
  const auto at = [&](double t) {
    const double s = std::fmod(t * speed, 4.0);
    return Eigen::Vector2d(s <= 2.0 ? s : 4.0 - s, 1.0);
  };
  const double now = 2.0 * lap_s + 1.6 / speed;
  const auto track = [&](double history_s) {
    MovingObstacleParams p = enabled_tracking();
    p.recurrence_history_s = history_s;
    MovingObstacleTracker tracker(p);
    for (int k = 0; 0.1 * k <= now + 1e-9; ++k) {
      std::vector<Eigen::Vector2d> pts;
      add_square(pts, at(0.1 * k), 0.15, k);
      tracker.update(pts, {0.0, -1.0}, 0.1 * k);
    }
    const auto moving = tracker.moving(now);
    EXPECT_EQ(moving.size(), 1u);
    return moving.empty() ? TrackedObstacle{} : moving[0];
  };
  const TrackedObstacle with = track(60.0), without = track(0.0);
  EXPECT_FALSE(with.recurrence.empty());
  EXPECT_LT((with.predict(now + 1.0) - at(now + 1.0)).norm(), 0.15);
  EXPECT_LT((with.predict(now + 2.0) - at(now + 2.0)).norm(), 0.2);
  EXPECT_TRUE(without.recurrence.empty());
  EXPECT_GT((without.predict(now + 1.0) - at(now + 1.0)).norm(), 0.6);
}

TEST(MovingObstacles, AMoverIsPredictedToTurnWhereAnotherTurnedGoingItsWay) {
  // One mover walks east from (0, 0) and turns north at (2, 0), at 0.8 m/s, and leaves; a second one
  // comes the same way 8 s later. At (1.6, 0) it is predicted to turn where the first one did.
  const double speed = 0.8;
  const auto way = [&](double s) {
    return s <= 2.0 ? Eigen::Vector2d(s, 0.0) : Eigen::Vector2d(2.0, std::min(s - 2.0, 2.0));
  };
  MovingObstacleTracker tracker(enabled_tracking());
  const double second_from = 8.0, now = second_from + 1.6 / speed;
  for (int k = 0; 0.1 * k <= now + 1e-9; ++k) {
    const double t = 0.1 * k;
    std::vector<Eigen::Vector2d> pts;
    if (t <= 4.0 / speed) add_square(pts, way(t * speed), 0.15, k);
    if (t >= second_from) add_square(pts, way((t - second_from) * speed), 0.15, k);
    tracker.update(pts, {1.0, -2.0}, t);
  }
  const auto moving = tracker.moving(now);
  ASSERT_EQ(moving.size(), 1u);
  EXPECT_FALSE(moving[0].recurrence.empty());
  EXPECT_LT((moving[0].predict(now + 1.0) - way(2.4)).norm(), 0.15);
  EXPECT_LT((moving[0].predict(now + 2.0) - way(3.2)).norm(), 0.2);
}

TEST(MovingObstacles, AMoverWalkingStraightThroughKeepsItsConstantVelocity) {
  MovingObstacleTracker tracker(enabled_tracking());
  const Eigen::Vector2d v(0.6, 0.2);
  for (int k = 0; k <= 60; ++k) {
    std::vector<Eigen::Vector2d> pts;
    add_square(pts, Eigen::Vector2d(-2.0, 0.5) + v * (0.1 * k), 0.15, k);
    tracker.update(pts, {0.0, -1.0}, 0.1 * k);
  }
  const auto moving = tracker.moving(6.0);
  ASSERT_EQ(moving.size(), 1u);
  EXPECT_TRUE(moving[0].recurrence.empty());
  EXPECT_LT((moving[0].predict(8.0) - (Eigen::Vector2d(-2.0, 0.5) + 8.0 * v)).norm(), 0.1);
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
  MovingObstacleParams r;
  r.recurrence_match_m = 0.0;
  EXPECT_ANY_THROW(r.validate());
  r.recurrence_match_m = 0.3;
  r.recurrence_history_s = -1.0;
  EXPECT_ANY_THROW(r.validate());
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
