#pragma once

#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/mapping/inflation.hpp"
#include "bipednav/mapping/local_costmap.hpp"
#include "bipednav/mapping/obstacle_layer.hpp"

namespace bipednav::mapping {

// What unexplored cells cost in the final map (section 4.5.1 counts them as free).
enum class UnknownCostMode { kFree, kUnknown, kLethal };
UnknownCostMode parse_unknown_cost_mode(const std::string& name);  // "free" | "unknown" | "lethal"

// The global map of section 4.5.1.
struct GlobalCostmapParams {
  double resolution_m = 0.1;     // used by default_geometry(); a given GridGeometry wins
  double default_size_m = 40.0;  // side of the default square map around the start
  double inscribed_radius_m = 0.2;
  double inflation_radius_m = 0.55;
  double cost_scaling_factor = 3.0;
  double obstacle_max_range_m = 10.0;
  double raytrace_max_range_m = 12.0;
  bool height_aware_clearing = false;  // see ObstacleLayerParams
  bool lidar_clearing = true;          // clear along LiDAR rays (false: LiDAR only marks)
  bool merge_local = true;             // copy the local map's obstacles and free cells in
  // Marks (the LiDAR's own and those copied from the local map, which bring the share of the local
  // lifetime they have used) that the LiDAR's rays pass over or under for this long with no return
  // confirming them go back to unexplored (see ObstacleLayer); 0: never. Marks out of the LiDAR's
  // view do not age.
  double mark_decay_s = 0.0;
  std::string unknown_cost_mode = "free";
  double rate_hz = 2.0;

  void validate() const;
  UnknownCostMode unknown_mode() const { return parse_unknown_cost_mode(unknown_cost_mode); }
  InflationParams inflation() const { return {inscribed_radius_m, inflation_radius_m, cost_scaling_factor}; }
  ObstacleLayerParams obstacle_layer() const {
    return {obstacle_max_range_m, raytrace_max_range_m, height_aware_clearing, decay_updates(mark_decay_s, rate_hz)};
  }

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("resolution_m", resolution_m);
    v("default_size_m", default_size_m);
    visit_layer_fields(v, *this);
    v("lidar_clearing", lidar_clearing);
    v("merge_local", merge_local);
    v("mark_decay_s", mark_decay_s);
    v("unknown_cost_mode", unknown_cost_mode);
    v("rate_hz", rate_hz);
  }
};

// A fixed grid holding walls and large obstructions. Its occupancy layer is three-state
// (kUnknown unexplored, kFree, kLethal); the final costmap inflates the lethal cells and gives
// unexplored cells the cost chosen by unknown_cost_mode (free: 0; unknown: 255; lethal: 254, not
// inflated). Every mutating call returns exactly the cells whose final cost changed, so an
// incremental planner (D* Lite) can repair its search.
class GlobalCostmap {
 public:
  explicit GlobalCostmap(const GridGeometry& geometry, const GlobalCostmapParams& params = {});

  // A default_size_m square at params.resolution_m centred on `start` (snapped to whole cells).
  static GridGeometry default_geometry(const Pose2& start, const GlobalCostmapParams& params = {});

  // LiDAR marking (and clearing if lidar_clearing), then the local map merged at its window:
  // local lethal cells mark, local cells seen free clear. `local` may be null.
  ChangeSet update(const Pose2& T_map_base, const std::vector<Observation>& lidar_obs, const LocalCostmap* local);

  // Replaces the occupancy layer with a known map (same width/height; kLethal, kUnknown, and
  // anything else counts as free), e.g. from read_map_server().
  ChangeSet set_occupancy(const Costmap2D& prior);

  // Recovery "clear costmaps": everything back to unexplored.
  ChangeSet clear();

  const Costmap2D& costmap() const { return costmap_; }      // final costs
  const Costmap2D& occupancy() const { return occupancy_; }  // kUnknown / kFree / kLethal
  const GridGeometry& geometry() const { return costmap_.geometry(); }
  const GlobalCostmapParams& params() const { return params_; }

 private:
  CellRect merge_local(const LocalCostmap& local);
  ChangeSet refresh(const CellRect& dirty);

  GlobalCostmapParams params_;
  UnknownCostMode unknown_mode_;
  ObstacleLayer obstacle_layer_;
  Inflator inflator_;
  Costmap2D occupancy_;
  Costmap2D costmap_;
  Costmap2D next_;                       // scratch: recomputed final costs of the dirty region
  std::vector<std::uint8_t> merge_;      // scratch: per global cell, local free (1) / lethal (2) seen
  std::vector<HeightBand> merge_bands_;  // scratch: per global cell, the heights of the local obstacles
  std::vector<float> merge_used_;        // scratch: per global cell, the least used lifetime of its local obstacles
};

}  // namespace bipednav::mapping
