#include "bench/tracking_harness.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "bipednav/common/cpu_time.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/footprint2d.hpp"
#include "bipednav/tracking/tracker.hpp"

namespace bipednav::bench {

namespace {

using tracking::MotObject;

// An actor at one time: its footprint (every part, any height) and the footprint's centre.
struct ActorTruth {
  MotObject object;
  std::vector<sim::Footprint2D> footprint;
  Eigen::Vector2d lo, hi;  // the footprint's bounding box
};

std::vector<sim::Footprint2D> actor_footprint(const sim::Actor& a, double t_s) {
  std::vector<sim::Footprint2D> out;
  const SE3 T_world_actor = a.pose_at(t_s);
  for (const auto& part : a.parts) {
    const auto f = sim::slab_footprints(part, T_world_actor, 0.0, 1e3);
    out.insert(out.end(), f.begin(), f.end());
  }
  return out;
}

// The footprint's bounding box and its centre (the actor's position).
Eigen::Vector2d footprint_box(const std::vector<sim::Footprint2D>& f, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (const auto& p : f) lo = lo.cwiseMin(p.bbox_min), hi = hi.cwiseMax(p.bbox_max);
  return 0.5 * (lo + hi);
}

// Whether the actor's velocity jumped within the window before t_s (TrackingEvaluationParams::turn_window_s).
bool turning(const sim::Actor& a, double t_s, const TrackingEvaluationParams& eval) {
  const double dt = eval.velocity_step_s;
  const int steps = static_cast<int>(std::ceil(eval.turn_window_s / dt));
  auto position = [&](int k) -> Eigen::Vector2d { return a.pose_at(t_s - k * dt).translation().head<2>(); };
  std::vector<Eigen::Vector2d> v;  // v[k]: the mean velocity over [t - (k+1) dt, t - k dt]
  Eigen::Vector2d later = position(0);
  for (int k = 0; k < steps + 2; ++k) {
    const Eigen::Vector2d earlier = position(k + 1);
    v.push_back((later - earlier) / dt);
    later = earlier;
  }
  for (int k = 0; k < steps; ++k)
    if ((v[static_cast<std::size_t>(k)] - v[static_cast<std::size_t>(k) + 2]).norm() >= eval.turn_jump_mps) return true;
  return false;
}

std::vector<ActorTruth> actor_truth(const sim::World& world, double t_s, const TrackingEvaluationParams& eval) {
  const double step_s = eval.velocity_step_s;
  std::vector<ActorTruth> out;
  for (std::size_t i = 0; i < world.actors.size(); ++i) {
    const sim::Actor& a = world.actors[i];
    ActorTruth& truth = out.emplace_back();
    truth.footprint = actor_footprint(a, t_s);
    truth.object.id = static_cast<int>(i);
    truth.object.position = footprint_box(truth.footprint, truth.lo, truth.hi);
    Eigen::Vector2d lo, hi;
    const Eigen::Vector2d ahead = footprint_box(actor_footprint(a, t_s + step_s), lo, hi);
    const Eigen::Vector2d behind = footprint_box(actor_footprint(a, t_s - step_s), lo, hi);
    truth.object.velocity = (ahead - behind) / (2.0 * step_s);
    truth.object.turning = turning(a, t_s, eval);
  }
  return out;
}

// Per actor, how many of the points (map frame) lie within margin_m of its footprint.
std::vector<int> points_on_actors(const std::vector<Eigen::Vector2d>& points_map, const Pose2& T_world_map,
                                  const std::vector<ActorTruth>& actors, double margin_m) {
  std::vector<int> count(actors.size(), 0);
  for (const auto& q : points_map) {
    const Eigen::Vector2d p = T_world_map.transform(q);
    for (std::size_t a = 0; a < actors.size(); ++a) {
      const ActorTruth& t = actors[a];
      if ((p.array() < t.lo.array() - margin_m).any() || (p.array() > t.hi.array() + margin_m).any()) continue;
      for (const auto& f : t.footprint) {
        if (sim::signed_distance(f, p) > margin_m) continue;
        ++count[a];
        break;
      }
    }
  }
  return count;
}

MotObject world_object(int id, const Eigen::Vector2d& p_map, const Eigen::Vector2d& v_map, const Pose2& T_world_map) {
  const Eigen::Vector2d v = T_world_map.transform(v_map) - T_world_map.transform(Eigen::Vector2d::Zero());
  return {id, T_world_map.transform(p_map), v};
}

// A ClearMot with the CPU time of the tracker it scores.
struct Scored {
  tracking::ClearMot mot;
  TrackerScore score;
};

// Scores every tracker at each local-map update of one run.
class RunScorer {
 public:
  RunScorer(const std::vector<TrackerVariant>& variants, const TrackingEvaluationParams& eval,
            const RobotProfile& robot, const perception::PerceptionParams& perception)
      : eval_(eval) {
    // The navigator's visibility model (Navigator's constructor): the ranges and obstacle height
    // of its perception.
    tracking::SensorVisibilityParams vis;
    vis.depth_max_range_m = perception.depth_max_range_m;
    vis.lidar_min_range_m = perception.lidar_min_range_m;
    vis.lidar_max_range_m = perception.lidar_max_range_m;
    vis.min_obstacle_height_m = perception.min_obstacle_height_m;
    for (const auto& v : variants) {
      trackers_.emplace_back(v.params, tracking::SensorVisibility(robot, vis));
      names_.push_back(v.name);
    }
    for (std::size_t i = 0; i < variants.size() + 2; ++i)
      scored_.push_back({tracking::ClearMot(eval.match_distance_m, eval.appearance_gap_s), {}});
  }

  void observe(const sim::Simulation& sim, const navigation::Navigator& nav) {
    const double t = nav.obstacle_points_stamp_s();
    if (t <= last_s_) return;
    last_s_ = t;
    ++evaluations_;
    const Pose2 T_world_base = sim.true_pose();
    const Pose2 T_world_map = T_world_base * nav.pose().inverse();
    const std::vector<ActorTruth> actors = actor_truth(sim.world(), t, eval_);
    const std::vector<int> seen = points_on_actors(nav.obstacle_points(), T_world_map, actors, eval_.point_margin_m);
    truths_.clear(), ignored_.clear();
    for (std::size_t a = 0; a < actors.size(); ++a) {
      const bool counts =
          seen[a] >= eval_.min_points && (actors[a].object.position - T_world_base.position()).norm() <= eval_.range_m;
      (counts ? truths_ : ignored_).push_back(actors[a].object);
    }
    for (std::size_t k = 0; k < trackers_.size(); ++k) {
      const double cpu0 = thread_cpu_ms();
      trackers_[k].set_static_map(nav.global_map().occupancy(), t);
      trackers_[k].update({t, nav.pose(), nav.obstacle_points(), nav.obstacle_heights()});
      scored_[k].score.cpu_ms += thread_cpu_ms() - cpu0;
      std::vector<MotObject> hyps;
      for (const auto& tr : trackers_[k].tracks())
        if (tr.confirmed() && tr.mover) hyps.push_back(world_object(tr.id, tr.position(), tr.velocity(), T_world_map));
      score(scored_[k], t, hyps, T_world_base);
      count_unmatched(scored_[k].score, trackers_[k], hyps, T_world_map);
    }
    score_baselines(nav, t, T_world_map, T_world_base);
    score_predictions(sim.world(), nav, t, T_world_map);
  }

  std::map<std::string, TrackerScore> scores() const {
    std::map<std::string, TrackerScore> out;
    for (std::size_t k = 0; k < scored_.size(); ++k) {
      TrackerScore s = scored_[k].score;
      s.mot = scored_[k].mot.summary();
      out[k < names_.size() ? names_[k] : (k == names_.size() ? kBaselineMoving : kBaselineAll)] = s;
    }
    return out;
  }
  long evaluations() const { return evaluations_; }

 private:
  void score(Scored& s, double t, const std::vector<MotObject>& hyps, const Pose2& T_world_base) {
    std::vector<char> in_region(hyps.size());
    for (std::size_t j = 0; j < hyps.size(); ++j)
      in_region[j] = (hyps[j].position - T_world_base.position()).norm() <= eval_.range_m;
    s.mot.add_frame(t, truths_, ignored_, hyps, in_region);
    ++s.score.updates;
  }

  // Adds the counted truths with no mover within match_distance_m, by the nearest evidence the
  // tracker holds (TrackerScore::unmatched).
  void count_unmatched(TrackerScore& s, const tracking::MultiObjectTracker& tracker,
                       const std::vector<MotObject>& movers, const Pose2& T_world_map) const {
    const double r = eval_.match_distance_m;
    auto near = [&](const Eigen::Vector2d& truth, const Eigen::Vector2d& p_map) {
      return (T_world_map.transform(p_map) - truth).norm() <= r;
    };
    const auto& tracks = tracker.tracks();
    const auto& detections = tracker.detections();
    for (const auto& truth : truths_) {
      const Eigen::Vector2d& q = truth.position;
      if (std::any_of(movers.begin(), movers.end(), [&](const MotObject& h) { return (h.position - q).norm() <= r; }))
        continue;
      const char* cause = "nothing";
      const tracking::Track* confirmed = nullptr;  // the nearest confirmed track within r
      for (const auto& tr : tracks)
        if (tr.confirmed() && near(q, tr.position()) &&
            (!confirmed || (T_world_map.transform(tr.position()) - q).norm() <
                               (T_world_map.transform(confirmed->position()) - q).norm()))
          confirmed = &tr;
      if (confirmed) {
        cause = "confirmed_not_mover";
        ++s.not_movers_by_test[tracking::motion_test_name(confirmed->motion_test)];
      } else if (std::any_of(tracks.begin(), tracks.end(),
                             [&](const tracking::Track& tr) { return near(q, tr.position()); }))
        cause = "tentative";
      else if (std::any_of(detections.begin(), detections.end(),
                           [&](const tracking::Detection& d) { return near(q, d.position); }))
        cause = "detection";
      ++s.unmatched[cause];
    }
  }

  void score_baselines(const navigation::Navigator& nav, double t, const Pose2& T_world_map,
                       const Pose2& T_world_base) {
    const auto& baseline = nav.moving_obstacles();
    std::vector<MotObject> moving, confirmed;
    for (const auto& m : baseline.moving(t))
      moving.push_back(world_object(m.id, m.predict(t), m.velocity, T_world_map));
    for (const auto& m : baseline.tracks()) {
      const bool fresh = m.coasting || t - m.last_seen_s <= baseline.params().max_track_age_s;
      if (m.hits >= baseline.params().min_hits && fresh)
        confirmed.push_back(world_object(m.id, m.predict(t), m.velocity, T_world_map));
    }
    score(scored_[names_.size()], t, moving, T_world_base);
    score(scored_[names_.size() + 1], t, confirmed, T_world_base);
  }

  // TrackerScore::prediction of the navigator's movers.
  void score_predictions(const sim::World& world, const navigation::Navigator& nav, double t,
                         const Pose2& T_world_map) {
    TrackerScore::Prediction& p = scored_[names_.size()].score.prediction;
    for (const auto& m : nav.moving_obstacles().moving(t)) {
      const Eigen::Vector2d now = T_world_map.transform(m.predict(t));
      const MotObject* truth = nullptr;
      for (const auto& o : truths_)
        if ((o.position - now).norm() <= eval_.match_distance_m &&
            (!truth || (o.position - now).norm() < (truth->position - now).norm()))
          truth = &o;
      if (!truth) continue;
      ++p.pairs;
      p.recurrent_pairs += !m.recurrence.empty();
      const sim::Actor& actor = world.actors[static_cast<std::size_t>(truth->id)];
      for (std::size_t k = 0; k < kPredictionHorizonsS.size(); ++k) {
        const double h = kPredictionHorizonsS[k];
        Eigen::Vector2d lo, hi;
        const Eigen::Vector2d then = footprint_box(actor_footprint(actor, t + h), lo, hi);
        p.squared_error_m2[k] += (T_world_map.transform(m.predict(t + h)) - then).squaredNorm();
        p.cv_squared_error_m2[k] += (T_world_map.transform(m.predict_constant_velocity(t + h)) - then).squaredNorm();
      }
    }
  }

  TrackingEvaluationParams eval_;
  std::vector<tracking::MultiObjectTracker> trackers_;
  std::vector<std::string> names_;
  std::vector<Scored> scored_;  // the variants', then kBaselineMoving's and kBaselineAll's
  std::vector<MotObject> truths_, ignored_;
  double last_s_ = -1e300;
  long evaluations_ = 0;
};

}  // namespace

TrackingRun run_tracking(const sim::Scenario& scenario, const std::string& robot, std::uint64_t seed,
                         const std::vector<TrackerVariant>& variants, const TrackingEvaluationParams& eval) {
  runner::RunOptions o;
  o.robot = robot;
  o.seed = seed;
  const RobotProfile profile = navigation::load_robot(robot);
  RunScorer scorer(variants, eval, profile, runner::navigator_params(profile, o).perception);
  o.on_step = [&](const sim::Simulation& sim, const SensorFrame&, const navigation::Navigator& nav, const Twist&) {
    scorer.observe(sim, nav);
  };
  TrackingRun out;
  out.scenario = scenario.name;
  out.robot = profile.name;
  out.seed = seed;
  try {
    const runner::RunResult r = runner::run_scenario(scenario, o);
    out.outcome = outcome_name(r.outcome.outcome);
    out.time_s = r.time_s;
    out.collisions = r.collisions;
  } catch (const std::exception& e) {
    out.outcome = std::string("error: ") + e.what();
  }
  out.scores = scorer.scores();
  out.evaluations = scorer.evaluations();
  return out;
}

}  // namespace bipednav::bench
