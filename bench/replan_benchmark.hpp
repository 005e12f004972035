#pragma once

#include <cstddef>

#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/mapping/inflation.hpp"
#include "bipednav/planning/global/global_planner.hpp"

namespace bipednav::bench {

// The reference's 6 x 30 m three-room simulation world as an occupancy grid (built in code so the
// benchmark does not depend on scenario files): outer and dividing walls with one door each, plus
// boxes and cylinders the robot does not know about in advance.
struct ThreeRoomsWorld {
  mapping::Costmap2D truth;  // walls and obstacles (kLethal), free elsewhere
  mapping::Costmap2D walls;  // the walls only: the robot's prior map
  Pose2 start;
  Pose2 goal;
};
ThreeRoomsWorld make_three_rooms_world(double resolution_m);

struct ReplanBenchParams {
  double resolution_m = 0.1;
  double sensor_radius_m = 3.0;  // obstacles within this distance of the robot are revealed
  double step_m = 0.1;           // robot advance between replans (0.5 m/s at the 5 Hz planner rate)
  double goal_tolerance_m = 0.2;
  int max_replans = 2000;
  mapping::InflationParams inflation{0.25, 0.8, 3.0};
  planning::global::GlobalPlannerParams planner;

  void validate() const;
};

// Per-replan figures of D* Lite (incremental) against A* (from scratch) on the same maps.
struct ReplanStats {
  int replans = 0;  // after the first plan
  bool reached_goal = false;
  double travelled_m = 0.0;
  std::size_t changed_cells = 0;
  int cost_mismatches = 0;  // replans where the two planners' path costs differ
  double first_dstar_ms = 0.0, first_astar_ms = 0.0;
  std::size_t first_dstar_expansions = 0, first_astar_expansions = 0;
  double dstar_mean_expansions = 0.0, astar_mean_expansions = 0.0;
  double dstar_mean_ms = 0.0, astar_mean_ms = 0.0;
  double dstar_max_ms = 0.0, astar_max_ms = 0.0;
  // The same in the calling thread's CPU time (the planners' own time_ms is wall time, which load inflates).
  double dstar_cpu_mean_ms = 0.0, astar_cpu_mean_ms = 0.0;
  double expansions_ratio = 0.0;  // A* mean / D* Lite mean
  double time_ratio = 0.0;        // wall time
  double cpu_time_ratio = 0.0;    // thread CPU time
};

// Drives a point robot along D* Lite's path through the three-room world: it starts with the
// walls only, reveals true obstacles within the sensor radius as it advances, inflates its map
// and passes the exact change set to D* Lite; A* plans from scratch on the same map each time.
ReplanStats run_replan_benchmark(const ReplanBenchParams& params);

// The point `distance_m` along a path (its end when the path is shorter), heading along it.
Pose2 advance_along(const Path& path, double distance_m);

}  // namespace bipednav::bench
