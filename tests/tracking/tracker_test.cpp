#include "bipednav/tracking/tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "bipednav/common/error.hpp"
#include "tracking/tracking_test_utils.hpp"

namespace bipednav::tracking {

namespace {

using test::Scan;
using test::scan_cylinder;

// A walker: a 0.25 m radius cylinder (1.7 m tall unless given) moving along a straight line.
struct Walker {
  Eigen::Vector2d start, velocity;
  double top_m = 1.7;
  Eigen::Vector2d at(double t_s) const { return start + velocity * t_s; }
};

// The confirmed track nearest to p within max_m, or null.
const Track* confirmed_near(const MultiObjectTracker& mot, const Eigen::Vector2d& p, double max_m) {
  const Track* best = nullptr;
  for (const auto& t : mot.tracks()) {
    if (!t.confirmed() || (t.position() - p).norm() > max_m) continue;
    if (best == nullptr || (t.position() - p).norm() < (best->position() - p).norm()) best = &t;
  }
  return best;
}

// One 10 Hz cycle of the tracker with the robot at `robot` seeing the walkers `visible` says it
// sees (all by default) at time t_s, with 2 cm range noise.
void cycle(MultiObjectTracker& mot, const Pose2& robot, const std::vector<Walker>& walkers, double t_s, Rng& rng,
           const std::function<bool(const Eigen::Vector2d&)>& visible = {}) {
  Scan scan;
  for (const auto& w : walkers)
    if (!visible || visible(w.at(t_s))) scan_cylinder(scan, robot.position(), w.at(t_s), 0.25, w.top_m, 0.02, rng);
  mot.update({t_s, robot, scan.points, scan.heights});
}

// One 10 Hz cycle seeing a person (a 1.7 m tall cylinder of 0.25 m radius) at c from the origin
// with 2 cm range noise; the confirmed track within 0.3 m of it, or null.
const Track* observe_person(MultiObjectTracker& mot, const Eigen::Vector2d& c, double t_s, Rng& rng) {
  Scan scan;
  scan_cylinder(scan, {0.0, 0.0}, c, 0.25, 1.7, 0.02, rng);
  mot.update({t_s, Pose2{}, scan.points, scan.heights});
  return confirmed_near(mot, c, 0.3);
}

}  // namespace

TEST(Tracker, ConstantVelocityTargetIsTrackedWithinItsNoise) {
  // A walker 3 m ahead crossing at 0.4 m/s, seen by a 2 cm noise scan from the origin.
  MultiObjectTracker mot;
  const Walker w{{3.0, -2.0}, {0.0, 0.4}};
  Rng rng(1);
  int id = -1;
  double max_position_err = 0.0, max_velocity_err = 0.0;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.1 * k;
    cycle(mot, Pose2{}, {w}, t, rng);
    const Track* track = confirmed_near(mot, w.at(t), 0.5);
    if (k == 2) {
      ASSERT_NE(track, nullptr) << "confirmed by its third hit (3 of 5)";
    }
    if (k < 2) continue;
    ASSERT_NE(track, nullptr) << "t " << t;
    if (id < 0) id = track->id;
    EXPECT_EQ(track->id, id) << "t " << t;
    if (t < 3.0) continue;  // converged after 3 s
    max_position_err = std::max(max_position_err, (track->position() - w.at(t)).norm());
    max_velocity_err = std::max(max_velocity_err, (track->velocity() - w.velocity).norm());
  }
  EXPECT_LT(max_position_err, 0.05);
  EXPECT_LT(max_velocity_err, 0.10);
  EXPECT_EQ(mot.tracks().size(), 1u);
}

TEST(Tracker, TwoCrossingTargetsKeepTheirIds) {
  // Their paths cross 2.3 s apart; at their closest (t = 5 s) their centres are 0.7 m apart.
  MultiObjectTracker mot;
  const std::vector<Walker> walkers{{{2.0, -1.5}, {0.3, 0.3}}, {{5.0, -0.8}, {-0.3, 0.3}}};
  Rng rng(2);
  std::map<int, int> id_of;  // walker -> track id
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.1 * k;
    cycle(mot, Pose2{}, walkers, t, rng);
    if (k < 3) continue;
    for (int i = 0; i < 2; ++i) {
      const Track* track = confirmed_near(mot, walkers[static_cast<std::size_t>(i)].at(t), 0.3);
      ASSERT_NE(track, nullptr) << "walker " << i << " t " << t;
      if (!id_of.count(i)) id_of[i] = track->id;
      EXPECT_EQ(track->id, id_of[i]) << "walker " << i << " t " << t;
    }
  }
  EXPECT_NE(id_of[0], id_of[1]);
}

TEST(Tracker, TargetLeavingViewCoastsThenIsDeleted) {
  // Digit's sensors: a 0.5 m tall object 1 m ahead moving to the left at 0.3 m/s leaves the front
  // camera's view at y = 1.14 m (t = 3.8 s) into the blind zone beside the robot, below the
  // LiDAR's lowest ring (which reaches 0.5 m at 3.6 m), where it stays.
  TrackerParams p;
  p.max_unseen_in_view_s = 0.5;
  p.max_unseen_out_of_view_s = 3.0;
  p.max_position_std_m = 10.0;  // the time limits decide here
  const SensorVisibility vis = test::digit_visibility();
  MultiObjectTracker mot(p, vis);
  const Walker w{{1.0, 0.0}, {0.0, 0.3}, 0.5};
  const auto seen = [&](const Eigen::Vector2d& c) { return vis.sees(Pose2{}, c, 0.5); };
  Rng rng(3);
  double last_seen = -1.0;
  int id = -1;
  for (int k = 0; k <= 80; ++k) {
    const double t = 0.1 * k;
    cycle(mot, Pose2{}, {w}, t, rng, seen);
    if (seen(w.at(t))) last_seen = t;
    if (k == 5) id = confirmed_near(mot, w.at(t), 0.3)->id;
    const double unseen = t - last_seen;
    const auto it =
        std::find_if(mot.tracks().begin(), mot.tracks().end(), [&](const Track& tr) { return tr.id == id; });
    if (k <= 5 || unseen < 1e-9) continue;
    if (unseen <= 2.95) {
      ASSERT_NE(it, mot.tracks().end()) << "coasting out of view, t " << t;
      EXPECT_EQ(it->status, TrackStatus::kCoasting);
      EXPECT_LT((it->position() - w.at(t)).norm(), 0.3) << "t " << t;
    } else if (unseen > 3.05) {
      EXPECT_EQ(it, mot.tracks().end()) << "deleted, t " << t;
    }
  }
  EXPECT_NEAR(last_seen, 3.8, 1e-9);
}

TEST(Tracker, TargetUnseenInViewIsDeletedSooner) {
  // The same walker vanishes at t = 1.5 s in front of the camera: deleted after 0.5 s unseen.
  const SensorVisibility vis = test::digit_visibility();
  MultiObjectTracker mot(TrackerParams{}, vis);
  const Walker w{{1.0, -0.3}, {0.0, 0.2}};
  Rng rng(4);
  for (int k = 0; k <= 30; ++k) {
    const double t = 0.1 * k;
    cycle(mot, Pose2{}, {w}, t, rng, [&](const Eigen::Vector2d&) { return t < 1.45; });
    ASSERT_TRUE(vis.sees(Pose2{}, w.at(t), 1.7));
    const bool tracked = confirmed_near(mot, w.at(t), 0.3) != nullptr;
    if (t > 0.25 && t < 1.95) {
      EXPECT_TRUE(tracked) << "t " << t;
    } else if (t > 2.05) {
      EXPECT_FALSE(tracked) << "t " << t;
    }
  }
}

TEST(Tracker, GatingRejectsAFarDetection) {
  MultiObjectTracker mot;
  Detection d;
  d.position = {3.0, 0.0};
  d.covariance = Eigen::Matrix2d::Identity() * 0.03 * 0.03;
  d.radius_m = 0.25;
  for (int k = 0; k < 10; ++k) mot.update_detections({d}, 0.1 * k, Pose2{});
  ASSERT_EQ(mot.tracks().size(), 1u);
  const int id = mot.tracks()[0].id;
  // 1 m away: outside the gate; the track misses and a new tentative track starts there.
  Detection far = d;
  far.position = {4.0, 0.0};
  mot.update_detections({far}, 1.0, Pose2{});
  ASSERT_EQ(mot.tracks().size(), 2u);
  EXPECT_EQ(mot.tracks()[0].id, id);
  EXPECT_EQ(mot.tracks()[0].status, TrackStatus::kCoasting);
  EXPECT_NEAR(mot.tracks()[0].position().x(), 3.0, 0.01);
  EXPECT_EQ(mot.tracks()[1].status, TrackStatus::kTentative);
  // 5 cm away: inside; it is the old track's again.
  Detection near = d;
  near.position = {3.05, 0.0};
  mot.update_detections({near}, 1.1, Pose2{});
  EXPECT_EQ(mot.tracks()[0].status, TrackStatus::kConfirmed);
  EXPECT_GT(mot.tracks()[0].position().x(), 3.0);
  // Of two detections in the gate the nearer one is taken (global nearest neighbour).
  Detection a = d, b = d;
  a.position = {3.25, 0.0}, b.position = {3.06, 0.01};
  mot.update_detections({a, b}, 1.2, Pose2{});
  EXPECT_LT(mot.tracks()[0].position().x(), 3.1);
}

TEST(Tracker, PredictionsGrowTheirCovarianceOverTheHorizon) {
  MultiObjectTracker mot;
  const Walker w{{3.0, -1.0}, {0.0, 0.5}};
  Rng rng(5);
  for (int k = 0; k <= 40; ++k) cycle(mot, Pose2{}, {w}, 0.1 * k, rng);
  const auto predictions = mot.predictions();
  ASSERT_EQ(predictions.size(), 1u);
  const auto& p = predictions[0];
  ASSERT_EQ(p.states.size(), 41u);  // 0 .. 4 s every 0.1 s
  EXPECT_NEAR(p.states.front().t_s, 4.0, 1e-9);
  EXPECT_NEAR(p.states.back().t_s, 8.0, 1e-9);
  EXPECT_LT((p.states.back().position - w.at(8.0)).norm(), 0.3);
  for (std::size_t k = 1; k < p.states.size(); ++k)
    EXPECT_GT(p.states[k].covariance.trace(), p.states[k - 1].covariance.trace());
  EXPECT_GT(p.states.back().covariance.trace(), 10.0 * p.states.front().covariance.trace());
}

TEST(Tracker, BadInputIsHandled) {
  MultiObjectTracker mot;
  // NaN points among a walker's scan change nothing; heights that do not match the points throw.
  Rng rng(6);
  Scan scan;
  scan_cylinder(scan, {0.0, 0.0}, {3.0, 0.0}, 0.25, 1.7, 0.02, rng);
  const std::size_t n = scan.points.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scan.points.emplace_back(nan, 1.0), scan.heights.push_back(0.5);
  scan.points.emplace_back(3.0, 0.0), scan.heights.push_back(nan);
  mot.update({0.0, Pose2{}, scan.points, scan.heights});
  ASSERT_EQ(mot.detections().size(), 1u);
  EXPECT_EQ(mot.detections()[0].points, static_cast<int>(n));
  scan.heights.pop_back();
  EXPECT_THROW(mot.update({0.1, Pose2{}, scan.points, scan.heights}), Error);
  // An empty cloud: no detections, the tentative track misses.
  mot.update({0.2, Pose2{}, {}, {}});
  EXPECT_TRUE(mot.detections().empty());
  ASSERT_EQ(mot.tracks().size(), 1u);
  // Times that do not advance, non-finite times and poses change nothing.
  mot.update_detections({}, 0.2, Pose2{});
  mot.update_detections({}, nan, Pose2{});
  mot.update_detections({}, 0.3, Pose2{nan, 0.0, 0.0});
  EXPECT_EQ(mot.tracks()[0].updates, 2);
  // A non-finite detection is ignored.
  Detection bad;
  bad.position = {nan, 0.0};
  mot.update_detections({bad}, 0.4, Pose2{});
  EXPECT_TRUE(mot.detections().empty());
  // Nonsense parameters are named.
  TrackerParams p;
  p.gate_chi2 = -1.0;
  EXPECT_THROW(MultiObjectTracker{p}, ParamError);
  p = {};
  p.motion_model = "ctrv";
  EXPECT_THROW(MultiObjectTracker{p}, ParamError);
  p = {};
  p.confirm_window = 2;
  EXPECT_THROW(p.validate(), ParamError);
  p = {};
  p.mover_min_span_s = p.mover_window_s + 0.1;  // never reached
  EXPECT_THROW(p.validate(), ParamError);
  p = {};
  p.free_birth_min_span_s = 0.0;
  EXPECT_THROW(p.validate(), ParamError);
}

TEST(Tracker, PointsOnTheStaticMapAreNoDetections) {
  // A wall's cells lethal for 5 s explain the points on it; a mover's fresh cells do not.
  mapping::Costmap2D occupancy = test::free_grid(0.0, 0.0, 10.0, 0.1);
  for (double y = -1.0; y <= 1.0; y += 0.05)
    occupancy.set_cost(*occupancy.geometry().world_to_cell(2.0, y), mapping::kLethal);
  MultiObjectTracker mot;
  mot.set_static_map(occupancy, 0.0);
  mot.set_static_map(occupancy, 5.0);
  std::vector<Eigen::Vector2d> points;
  for (double y = -0.3; y <= 0.3; y += 0.02) points.emplace_back(2.0, y);  // on the wall
  Rng rng(7);
  Scan scan;
  scan_cylinder(scan, {0.0, 0.0}, {3.0, 2.0}, 0.25, 1.7, 0.02, rng);
  for (const auto& p : scan.points)
    occupancy.set_cost(*occupancy.geometry().world_to_cell(p.x(), p.y()), mapping::kLethal);
  mot.set_static_map(occupancy, 5.5);
  points.insert(points.end(), scan.points.begin(), scan.points.end());
  mot.update({5.5, Pose2{}, points, {}});
  ASSERT_EQ(mot.detections().size(), 1u);
  EXPECT_LT((mot.detections()[0].position - Eigen::Vector2d(3.0, 2.0)).norm(), 0.05);
}

TEST(Tracker, WalkerBecomesAMoverAndStaysOneWhenItStops) {
  // 0.4 m/s for 5 s, then standing for 8 s, 3 m ahead.
  MultiObjectTracker mot;
  Rng rng(8);
  const auto at = [](double t) { return Eigen::Vector2d(3.0, -1.0 + 0.4 * std::min(t, 5.0)); };
  double mover_s = -1.0;
  for (int k = 0; k <= 130; ++k) {
    const double t = 0.1 * k;
    const Track* track = observe_person(mot, at(t), t, rng);
    if (k >= 3) {
      ASSERT_NE(track, nullptr) << "t " << t;
    }
    if (track != nullptr && track->mover && mover_s < 0.0) mover_s = t;
    if (t > 3.0) {
      EXPECT_TRUE(track->mover) << "t " << t;
    }
  }
  // Detections spanning mover_min_span_s (1.2 s) from the first one.
  EXPECT_GT(mover_s, 1.15);
  EXPECT_LT(mover_s, 1.65);
  EXPECT_TRUE(confirmed_near(mot, at(13.0), 0.2)->proven);
  EXPECT_EQ(mot.predictions().size(), 1u);
}

TEST(Tracker, MoverTurningOnTheSpotKeepsItsIdAndStaysAMover) {
  // 1.2 m/s along y for 2.5 s, 3 m ahead, then straight back (the generated people turn so): the
  // constant-velocity prediction runs 0.24 m past the walker in the cycle after the turn, outside
  // the gate; the detection is the track's again, being within the distance its speed covers
  // since it was last seen.
  MultiObjectTracker mot;
  Rng rng(9);
  const auto at = [](double t) { return Eigen::Vector2d(3.0, -1.5 + 1.2 * (t < 2.5 ? t : 5.0 - t)); };
  int id = -1;
  for (int k = 0; k <= 50; ++k) {
    const double t = 0.1 * k;
    const Track* track = observe_person(mot, at(t), t, rng);
    if (k < 3) continue;
    if (track == nullptr) track = confirmed_near(mot, at(t), 0.6);  // a cycle after the turn
    ASSERT_NE(track, nullptr) << "t " << t;
    if (id < 0) id = track->id;
    EXPECT_EQ(track->id, id) << "t " << t;
    if (t > 2.0) {
      EXPECT_TRUE(track->mover) << "t " << t;
    }
  }
  EXPECT_EQ(mot.predictions().size(), 1u);
}

TEST(Tracker, PacerFirstSeenMidwayIsProvenOnceItsWalkSpansTheProof) {
  // Pacing 1.6 m to and fro at 0.5 m/s across the line of sight, first seen in the middle: it is
  // never 1 m from where it was first seen, but its positions span 1.6 m, so it is a mover for good
  // (through every turn) from its first far end on.
  MultiObjectTracker mot;
  Rng rng(10);
  const auto at = [](double t) {
    const double u = std::fmod(t * 0.5 + 0.8, 3.2);  // 0 .. 3.2 m along the walk and back
    return Eigen::Vector2d(3.0, -0.8 + (u < 1.6 ? u : 3.2 - u));
  };
  double proven_s = -1.0;
  int id = -1;
  for (int k = 0; k <= 160; ++k) {
    const double t = 0.1 * k;
    const Track* track = observe_person(mot, at(t), t, rng);
    if (k < 3) continue;
    ASSERT_NE(track, nullptr) << "t " << t;
    if (id < 0) id = track->id;
    EXPECT_EQ(track->id, id) << "t " << t;  // the track that started midway
    EXPECT_LT((at(t) - at(0.0)).norm(), 0.81);
    if (proven_s < 0.0 && track->proven) proven_s = t;
    if (proven_s >= 0.0) {
      EXPECT_TRUE(track->mover) << "t " << t;
    }
  }
  // Its far ends are 1.6 s and 4.8 s in; the first full leg (0.8 .. -0.8 m) spans the proof at
  // about 3.6 s.
  EXPECT_GT(proven_s, 3.0);
  EXPECT_LT(proven_s, 4.5);
}

TEST(Tracker, PersonAppearingInFreeSpaceIsAMoverSooner) {
  // A walker first detected at t = 0 where the map has seen free floor for 4 s is a mover after
  // free_birth_min_span_s (0.6 s) of detections; where the map has seen nothing, after
  // mover_min_span_s (1.2 s).
  for (const bool seen_free : {true, false}) {
    MultiObjectTracker mot;
    const mapping::Costmap2D free = test::free_grid(3.0, 0.0, 10.0, 0.1);
    const mapping::Costmap2D unknown(free.geometry(), mapping::kUnknown);
    for (int k = -40; k < 0; ++k) mot.set_static_map(seen_free ? free : unknown, 0.1 * k);
    Rng rng(11);
    const auto at = [](double t) { return Eigen::Vector2d(3.0, -1.0 + 0.5 * t); };
    double mover_s = -1.0;
    for (int k = 0; k <= 20 && mover_s < 0.0; ++k) {
      const double t = 0.1 * k;
      mot.set_static_map(seen_free ? free : unknown, t);
      const Track* track = observe_person(mot, at(t), t, rng);
      if (track != nullptr && track->mover) mover_s = t;
    }
    const double span_s = seen_free ? 0.6 : 1.2;  // a cycle more when the 5 standard errors need it
    EXPECT_GT(mover_s, span_s - 0.05) << (seen_free ? "free" : "unknown");
    EXPECT_LT(mover_s, span_s + 0.15) << (seen_free ? "free" : "unknown");
  }
}

TEST(Tracker, WallRevealedBitByBitIsNoMover) {
  // The robot sees a wall along y = 2 up to x = s(t) = 1 + 0.4 t (revealed as it walks), and the
  // map knows the wall up to 0.3 m short of that: the fresh piece slides at 0.4 m/s like a mover,
  // but where it was stays occupied. The same piece without the wall behind it is a mover.
  TrackerParams p;
  p.static_age_s = 0.0;
  for (const bool wall_behind : {true, false}) {
    MultiObjectTracker mot(p);
    mapping::Costmap2D occupancy = test::free_grid(3.0, 2.0, 12.0, 0.1);
    bool mover = false;
    for (int k = 0; k <= 60; ++k) {
      const double t = 0.1 * k, s = 1.0 + 0.4 * t;
      std::vector<Eigen::Vector2d> points;
      std::vector<double> heights;
      for (double x = wall_behind ? 0.0 : s - 0.5; x <= s; x += 0.02) {
        for (const double z : {0.3, 0.6, 0.9}) points.emplace_back(x, 2.0), heights.push_back(z);
        if (x < s - 0.3) occupancy.set_cost(*occupancy.geometry().world_to_cell(x, 2.0), mapping::kLethal);
      }
      mot.set_static_map(occupancy, t);
      mot.update({t, Pose2{s - 1.0, 0.0, 0.0}, points, heights});
      for (const auto& tr : mot.tracks()) mover = mover || tr.mover;
    }
    EXPECT_EQ(mover, !wall_behind);
  }
}

}  // namespace bipednav::tracking
