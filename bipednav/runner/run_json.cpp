#include "bipednav/runner/run_json.hpp"

#include "bipednav/common/outcome.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::runner {

namespace {

nlohmann::json pose_json(const Pose2& p) { return {{"x_m", p.x}, {"y_m", p.y}, {"yaw_rad", p.theta}}; }

nlohmann::json outcome_json(const Result& r) {
  return {{"outcome", std::string(outcome_name(r.outcome))}, {"outcome_code", code(r.outcome)}, {"message", r.message}};
}

}  // namespace

nlohmann::json run_result_json(const RunResult& r) {
  nlohmann::json j = {
      {"scenario", r.scenario}, {"robot", r.robot}, {"seed", r.seed}, {"success", r.success}, {"verdict", r.verdict}};
  const nlohmann::json navigator = outcome_json(r.outcome);
  j.update({{"navigator_outcome", navigator["outcome"]},
            {"navigator_outcome_code", navigator["outcome_code"]},
            {"navigator_message", navigator["message"]}});
  j["collisions"] = r.collisions;
  if (const auto& c = r.first_collision) {
    j["first_collision"] = {{"time_s", c->time_s},
                            {"x_m", c->point.x()},
                            {"y_m", c->point.y()},
                            {"obstacle", c->obstacle},
                            {"penetration_m", c->penetration_m},
                            {"robot_standing", sim::robot_standing(*c)}};
  }
  j.update({{"time_s", r.time_s},
            {"first_arrival_s", r.first_arrival_s ? nlohmann::json(*r.first_arrival_s) : nlohmann::json(nullptr)},
            {"final_true_pose", pose_json(r.final_true_pose)},
            {"final_estimated_pose", pose_json(r.final_estimated_pose)}});
  j.update({{"path_length_m", r.path_length_m},
            {"min_clearance_m", r.min_clearance_m},
            {"goal_error_m", r.goal_error_m},
            {"goal_error_rad", r.goal_error_rad},
            {"localization_error_m", r.localization_error_m},
            {"replans", r.replans},
            {"recoveries", r.recoveries}});
  nlohmann::json log = nlohmann::json::array();
  for (const auto& rec : r.recovery_log) {
    nlohmann::json e = outcome_json(rec.result);
    e.update({{"name", rec.name}, {"start_s", rec.start_s}, {"end_s", rec.end_s}});
    log.push_back(e);
  }
  j["recovery_log"] = log;
  j.update({{"real_time_factor", r.real_time_factor},
            {"wall_s", r.wall_s},
            {"cpu_s", r.cpu_s},
            {"cpu_real_time_factor", r.cpu_real_time_factor},
            {"stage_cpu_ms", r.stage_cpu_ms},
            {"goals_given", r.goals_given}});
  const sim::FaultCounters& f = r.faults;
  j["faults"] = {{"sweeps_dropped", f.sweeps_dropped},     {"depth_points_nan", f.depth_points_nan},
                 {"odometry_jumps", f.odometry_jumps},     {"odometry_slipped", f.odometry_slipped},
                 {"messages_delayed", f.messages_delayed}, {"messages_reordered", f.messages_reordered},
                 {"commands_dropped", f.commands_dropped}};
  j.update({{"watchdog_stops", r.watchdog_stops}, {"watchdog_stopped_s", r.watchdog_stopped_s}});
  return j;
}

}  // namespace bipednav::runner
