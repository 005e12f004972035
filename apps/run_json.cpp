#include "apps/run_json.hpp"

#include "bipednav/common/outcome.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::app {

nlohmann::json run_result_json(const runner::RunResult& r) {
  nlohmann::json j;
  j["scenario"] = r.scenario;
  j["robot"] = r.robot;
  j["seed"] = r.seed;
  j["success"] = r.success;
  j["verdict"] = r.verdict;
  j["navigator_outcome"] = std::string(outcome_name(r.outcome.outcome));
  j["navigator_outcome_code"] = code(r.outcome.outcome);
  j["navigator_message"] = r.outcome.message;
  j["collisions"] = r.collisions;
  if (r.first_collision) {
    j["first_collision"] = {{"time_s", r.first_collision->time_s},
                            {"x_m", r.first_collision->point.x()},
                            {"y_m", r.first_collision->point.y()},
                            {"obstacle", r.first_collision->obstacle},
                            {"penetration_m", r.first_collision->penetration_m},
                            {"robot_standing", sim::robot_standing(*r.first_collision)}};
  }
  j["time_s"] = r.time_s;
  j["first_arrival_s"] = r.first_arrival_s ? nlohmann::json(*r.first_arrival_s) : nlohmann::json(nullptr);
  const auto pose = [](const Pose2& p) { return nlohmann::json{{"x_m", p.x}, {"y_m", p.y}, {"yaw_rad", p.theta}}; };
  j["final_true_pose"] = pose(r.final_true_pose);
  j["final_estimated_pose"] = pose(r.final_estimated_pose);
  j["path_length_m"] = r.path_length_m;
  j["min_clearance_m"] = r.min_clearance_m;
  j["goal_error_m"] = r.goal_error_m;
  j["goal_error_rad"] = r.goal_error_rad;
  j["localization_error_m"] = r.localization_error_m;
  j["replans"] = r.replans;
  j["recoveries"] = r.recoveries;
  j["recovery_log"] = nlohmann::json::array();
  for (const auto& rec : r.recovery_log)
    j["recovery_log"].push_back({{"name", rec.name},
                                 {"start_s", rec.start_s},
                                 {"end_s", rec.end_s},
                                 {"outcome", std::string(outcome_name(rec.result.outcome))},
                                 {"outcome_code", code(rec.result.outcome)},
                                 {"message", rec.result.message}});
  j["real_time_factor"] = r.real_time_factor;
  j["wall_s"] = r.wall_s;
  j["cpu_s"] = r.cpu_s;
  j["cpu_real_time_factor"] = r.cpu_real_time_factor;
  j["stage_cpu_ms"] = r.stage_cpu_ms;
  j["goals_given"] = r.goals_given;
  const sim::FaultCounters& f = r.faults;
  j["faults"] = {{"sweeps_dropped", f.sweeps_dropped},     {"depth_points_nan", f.depth_points_nan},
                 {"odometry_jumps", f.odometry_jumps},     {"odometry_slipped", f.odometry_slipped},
                 {"messages_delayed", f.messages_delayed}, {"messages_reordered", f.messages_reordered},
                 {"commands_dropped", f.commands_dropped}};
  j["watchdog_stops"] = r.watchdog_stops;
  j["watchdog_stopped_s"] = r.watchdog_stopped_s;
  return j;
}

}  // namespace bipednav::app
