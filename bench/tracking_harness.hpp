#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bipednav/sim/scenario.hpp"
#include "bipednav/tracking/mot_metrics.hpp"
#include "bipednav/tracking/tracker_params.hpp"

// The harness of `bipednav bench tracking`: closed-loop runs of the navigator in the simulator
// with trackers fed from the navigator's local-map input, scored against the simulator's actors.
namespace bipednav::bench {

// A multi-object tracker under test: a name and its parameters.
struct TrackerVariant {
  std::string name;
  tracking::TrackerParams params;
};

// The evaluation (TrackingEvaluationParams): the actors that count at an evaluation time are
// those within range_m of the robot that the sensors returned at least min_points obstacle points
// from in the cycle (within point_margin_m of the actor's footprint): seen, so occlusion by walls
// and the sensors' blind zones are the simulator's own. Tracks are taken into the world frame
// through the robot's true pose (T_world_map = T_world_base_true * T_map_base_estimated^-1), so
// the scores are the tracker's relative to the robot, without the localization's drift.
struct TrackingEvaluationParams {
  double range_m = 6.0;
  int min_points = 3;
  double point_margin_m = 0.1;
  double match_distance_m = 0.5;  // CLEAR MOT's threshold
  double appearance_gap_s = 1.0;  // unseen this long: in view again is a new appearance
  double velocity_step_s = 0.05;  // truth velocity: central difference of Actor::pose_at over +-this
  // An actor is turning (MotObject::turning) for turn_window_s after its velocity changed by at
  // least turn_jump_mps between two velocities (differences over velocity_step_s) 2
  // velocity_step_s apart: an acceleration of 5 m/s^2 and more at the defaults, beyond a walking
  // person's, the instant turn of a waypoint trajectory.
  double turn_window_s = 0.5;
  double turn_jump_mps = 0.5;
};

// The horizons at which the movers' predictions are scored (TrackerScore::Prediction).
inline constexpr std::array<double, 3> kPredictionHorizonsS{1.0, 2.0, 3.0};

// Scores of one tracker over one run (or pooled over runs) and its CPU time per update.
struct TrackerScore {
  tracking::MotSummary mot;
  long updates = 0;
  double cpu_ms = 0.0;
  // The counted truths with no mover of the tracker within match_distance_m, by the nearest thing
  // the tracker holds within that distance: "confirmed_not_mover", "tentative", "detection" (a
  // detection of the cycle but no track), "nothing". The variants' only (the baselines: empty).
  std::map<std::string, long> unmatched;
  // Of those "confirmed_not_mover", by the mover test that held the nearest confirmed track back
  // (tracking::MotionTest: "short_window", "still", "flat", "origin_occupied").
  std::map<std::string, long> not_movers_by_test;
  // The navigator's movers' predictions (kBaselineMoving only): each mover within
  // match_distance_m of a counted truth, its predicted position kPredictionHorizonsS ahead against
  // the truth's position then, summed squared errors; beside them the constant-velocity
  // prediction of the same tracks (position + velocity * horizon), the reference.
  struct Prediction {
    long pairs = 0, recurrent_pairs = 0;                                    // recurrent: predicted by their recurrence
    std::array<double, kPredictionHorizonsS.size()> squared_error_m2{};     // per horizon
    std::array<double, kPredictionHorizonsS.size()> cv_squared_error_m2{};  // per horizon
  };
  Prediction prediction;
};

struct TrackingRun {
  std::string scenario, robot;
  std::uint64_t seed = 0;
  std::string outcome;  // the navigation's outcome, or what the run threw
  double time_s = 0.0;
  int collisions = 0;
  long evaluations = 0;                        // local-map updates scored
  std::map<std::string, TrackerScore> scores;  // by tracker name: the variants, then the baselines
};

// The names under which the navigator's own MovingObstacleTracker is scored: its moving() tracks
// (what the navigator yields to) and every track it has confirmed (min_hits; fresh or coasting).
inline constexpr const char* kBaselineMoving = "baseline_moving_obstacle_tracker";
inline constexpr const char* kBaselineAll = "baseline_all_confirmed_tracks";

// One closed-loop run of `scenario` with `robot` (a profile name or file) and `seed`, every variant
// fed each local-map update's obstacle points and the global map's occupancy as static map.
TrackingRun run_tracking(const sim::Scenario& scenario, const std::string& robot, std::uint64_t seed,
                         const std::vector<TrackerVariant>& variants, const TrackingEvaluationParams& eval = {});

}  // namespace bipednav::bench
