#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/outcome.hpp"
#include "bipednav/localization/corrected_odometry.hpp"
#include "bipednav/mapping/heightmap_fusion.hpp"
#include "bipednav/perception/voxel_grid.hpp"
#include "bipednav/planning/footstep/footstep_planner.hpp"

namespace bipednav::navigation {

// Footstep navigation among 3D obstacles (second reference): GICP-corrected kinematic odometry,
// a Kalman heightmap in the odometry frame, ARA* footstep plans, replanning when new map data
// invalidates the plan or the robot deviates from it.
struct FootstepNavigatorParams {
  planning::footstep::FootstepPlannerParams planner = default_planner();
  mapping::HeightmapFusionParams fusion;
  localization::CorrectedOdometryParams odometry = default_odometry();
  bool gicp_correction = true;         // false: plain kinematic odometry
  double gicp_voxel_m = 0.03;          // clouds are downsampled to this before GICP
  double replan_deviation_m = 0.03;    // replan when the stance foot is this far from the plan
  double replan_deviation_rad = 0.15;  // ... or turned this far
  double obstacle_margin_m = 0.03;     // walls and blocks grow by this for the planner (obstacle_margin.hpp)
  double obstacle_step_m = 0.08;       // ... where the terrain rises by more than this (Nao steps onto 7 cm)
  std::size_t max_plans = 60;          // give up (PLAN_FAILURE) after this many plans
  // When no plan reaches the goal from the stance (execution error left a foot next to a riser
  // or a wall), take up to this many corrective planar steps in a row (back, in place, turn,
  // aside: the first that is safe) and replan from where the foot really lands.
  std::size_t max_recovery_steps = 3;

  void validate() const;
  // Deterministic planning in the loop: the first ARA* solution with epsilon 3 and no time
  // limit, capped by expansions (a run is reproducible bit for bit).
  static planning::footstep::FootstepPlannerParams default_planner();
  // GICP between the views of consecutive stances: the kinematic odometry is good to a few
  // centimetres per step, so matches are sought within 0.1 m and a correction may move by at
  // most 3 cm / 0.03 rad per update (wall-only scenes leave directions poorly constrained).
  static localization::CorrectedOdometryParams default_odometry();

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("gicp_correction", gicp_correction);
    v("gicp_voxel_m", gicp_voxel_m);
    v("replan_deviation_m", replan_deviation_m);
    v("replan_deviation_rad", replan_deviation_rad);
    v("obstacle_margin_m", obstacle_margin_m);
    v("obstacle_step_m", obstacle_step_m);
    v("max_plans", max_plans);
    v("max_recovery_steps", max_recovery_steps);
    v.group("planner", planner);
    v.group("fusion", fusion);
    v.group("odometry", odometry);
  }
};

// What to do next: a step (the landing foot in the map frame and its action), or the end of the
// navigation with its outcome (SUCCESS, NO_PATH_FOUND, BLOCKED_GOAL, PLAN_OUT_OF_MAP, ...).
// One depth image: the cloud in its sensor frame and where the sensor was on the base.
struct DepthView {
  PointCloud cloud_sensor;
  SE3 T_base_sensor = SE3::Identity();
};

struct StepDecision {
  bool done = false;
  Result result;
  planning::footstep::Footstep target;
  const planning::footstep::FootstepAction* action = nullptr;
  bool replanned = false;
};

class FootstepNavigator {
 public:
  // `map_geometry` is the heightmap's grid in the map (corrected odometry) frame.
  FootstepNavigator(const FootstepNavigatorParams& params, const mapping::GridGeometry& map_geometry);

  void set_goal(const Pose2& goal_map);
  // The views taken from one stance (the head turned left and right) with the base's odometry
  // pose: one merged cloud corrects the odometry against the previous stance's (eq. 1), then
  // each view updates the Kalman heightmap (eq. 2-3) in the corrected frame.
  void observe(const std::vector<DepthView>& views, const SE3& T_odom_base);
  // The next step from the odometry pose of the stance (supporting) foot and, when known, of the
  // other foot: a swing foot that stands higher than the stance foot (mid-way down a step) keeps
  // its lifted height on the way to its landing, and the plans from here check the first step so
  // (FootstepPlanner::plan's swing_z_m).
  StepDecision next(const planning::footstep::Footstep& odom_stance,
                    const std::optional<planning::footstep::Footstep>& odom_swing = std::nullopt);

  // Odometry frame -> map frame: the x, y, yaw part of the GICP correction (height, roll and
  // pitch of the kinematic odometry come from the leg kinematics and the IMU, which do not drift;
  // GICP on scenes of mostly planar walls leaves them poorly constrained).
  planning::footstep::Footstep to_map(const planning::footstep::Footstep& odom) const;
  SE3 T_map_odom() const { return se3_from_pose2(pose2_from_se3(odometry_.correction())); }
  const mapping::Heightmap& map() const { return fusion_.map(); }
  const planning::footstep::FootstepPlan& plan() const { return plan_; }
  // plan().steps[plan_cursor()] is the stance foot (after next() returned a step: its target).
  std::size_t plan_cursor() const { return cursor_; }
  std::size_t plans() const { return plans_; }
  std::size_t corrections() const { return corrections_; }
  std::size_t recoveries() const { return recoveries_; }  // corrective steps taken
  const planning::footstep::FootstepPlanner& planner() const { return planner_; }

 private:
  bool close_to_plan(const planning::footstep::Footstep& stance) const;  // plan_.steps[cursor_] must exist
  // `swing_z`: the swing foot's height in the map frame, if known.
  bool needs_replan(const planning::footstep::Footstep& stance, std::optional<double> swing_z);
  Result replan(const planning::footstep::Footstep& stance, std::optional<double> swing_z);
  // A corrective step from `stance` after a failed plan (plan_ becomes that one step); false
  // when no planar step is safe.
  bool recover(const planning::footstep::Footstep& stance, std::optional<double> swing_z);
  planning::footstep::FootstepPlan remaining() const;
  const mapping::Heightmap& planning_map();  // the heightmap with the obstacle margin

  FootstepNavigatorParams params_;
  planning::footstep::FootstepPlanner planner_;
  mapping::HeightmapFusion fusion_;
  localization::CorrectedOdometry odometry_;
  perception::VoxelGrid voxel_;
  Pose2 goal_;
  bool has_goal_ = false, map_changed_ = false, planning_map_stale_ = true;
  mapping::Heightmap planning_map_;
  planning::footstep::FootstepPlan plan_;
  std::size_t cursor_ = 0;  // plan_.steps[cursor_] is the current stance foot
  std::size_t plans_ = 0, corrections_ = 0, recoveries_ = 0, recoveries_in_row_ = 0;
};

}  // namespace bipednav::navigation
