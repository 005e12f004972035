#pragma once

#include <string_view>
#include <vector>

#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "bipednav/planning/local/homotopy.hpp"
#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/plan_utils.hpp"
#include "bipednav/planning/local/teb_params.hpp"

namespace bipednav::planning::local {

// The Timed-Elastic-Band local planner (thesis 5.2) for a walking robot modelled as a
// differential drive. One compute() per control cycle: local goal and via points from the global
// plan, obstacles from the local costmap, homotopy candidates optimised and selected, feasibility
// check, then the first interval's velocity clamped to the limits.
class TebPlanner : public LocalPlanner {
 public:
  explicit TebPlanner(TebParams params);

  LocalPlanResult compute(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                          const mapping::Costmap2D& local_costmap, double now_s) override;
  void reset() override;
  std::string_view name() const override { return "teb"; }

  const TebParams& params() const { return params_; }
  // The obstacles and candidates of the last compute() (for display and tests).
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  const std::vector<BandCandidate>& candidates() const { return homotopy_.candidates(); }
  // The tracker's moving obstacles at now_s for the band (TebOptimizerParams::dynamic_obstacles; empty
  // without it).
  std::vector<TebMovingObstacle> band_moving(double now_s) const;

 private:
  LocalPlanResult plan(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                       const mapping::Costmap2D& local_costmap, double now_s);
  LocalPlanResult finish(LocalPlanResult r, const Twist& desired, const Twist& current);
  VelocityLimits command_limits() const;

  TebParams params_;
  HomotopyPlanner homotopy_;
  OscillationDetector oscillation_;
  std::vector<Obstacle> obstacles_;
  ObstacleScratch obstacle_scratch_;  // extract_obstacles' buffers, kept between cycles
  bool holding_goal_ = false;         // approach_goal's hysteresis
};

// The first interval's velocity (eq. 5.8 with the exact sign, eq. 5.9); zero for a degenerate band.
Twist band_command(const TebBand& band);

}  // namespace bipednav::planning::local
