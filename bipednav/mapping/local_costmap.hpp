#pragma once

#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/mapping/inflation.hpp"
#include "bipednav/mapping/obstacle_layer.hpp"

namespace bipednav::mapping {

// The inflation and obstacle-layer fields that both costmaps' parameters have (their inflation() and
// obstacle_layer()), listed once for their visit_fields.
template <class V, class Costmap>
void visit_layer_fields(V& v, Costmap& p) {
  v("inscribed_radius_m", p.inscribed_radius_m);
  v("inflation_radius_m", p.inflation_radius_m);
  v("cost_scaling_factor", p.cost_scaling_factor);
  v("obstacle_max_range_m", p.obstacle_max_range_m);
  v("raytrace_max_range_m", p.raytrace_max_range_m);
  v("height_aware_clearing", p.height_aware_clearing);
}

// The local map of section 4.5.2: a rolling window centred on the robot.
struct LocalCostmapParams {
  double size_m = 8.0;
  double resolution_m = 0.05;
  double inscribed_radius_m = 0.2;
  double inflation_radius_m = 0.55;
  double cost_scaling_factor = 3.0;
  double obstacle_max_range_m = 4.0;
  double raytrace_max_range_m = 5.0;
  bool height_aware_clearing = false;  // see ObstacleLayerParams
  // A mark no return confirms for this long goes back to unknown (see ObstacleLayer); 0: never.
  double mark_decay_s = 0.0;
  double rate_hz = 10.0;

  void validate() const;
  InflationParams inflation() const { return {inscribed_radius_m, inflation_radius_m, cost_scaling_factor}; }
  ObstacleLayerParams obstacle_layer() const {
    return {obstacle_max_range_m, raytrace_max_range_m, height_aware_clearing, decay_updates(mark_decay_s, rate_hz)};
  }

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("size_m", size_m);
    v("resolution_m", resolution_m);
    visit_layer_fields(v, *this);
    v("mark_decay_s", mark_decay_s);
    v("rate_hz", rate_hz);
  }
};

// Obstacle layer (marking + ray-trace clearing) and inflation on an axis-aligned window of the
// map frame that follows the robot. Cells that enter the window start unknown and count as free.
class LocalCostmap {
 public:
  explicit LocalCostmap(const LocalCostmapParams& params = {});

  // Re-centres the window on the robot (snapped to whole cells), applies the observations and
  // re-inflates. Returns the cells (in the new window's coordinates) whose final cost differs from
  // before the update; cells that just entered the window are compared against free.
  ChangeSet update(const Pose2& T_map_base, const std::vector<Observation>& observations);

  const Costmap2D& costmap() const { return costmap_; }      // final inflated costs
  const Costmap2D& obstacles() const { return obstacles_; }  // kLethal at obstacles, kFree elsewhere
  // Three-state layer: kUnknown (not seen since the cell entered the window), kFree, kLethal.
  const Costmap2D& observed() const { return layer_; }
  // The heights an obstacle cell of observed() was seen at (empty when not known).
  const HeightBand& obstacle_band(int x, int y) const { return obstacle_layer_.band(x, y); }
  // Updates whose rays passed obstacle cell (x, y) unconfirmed (see ObstacleLayer::mark_age).
  int mark_age(int x, int y) const { return obstacle_layer_.mark_age(x, y); }
  const GridGeometry& geometry() const { return costmap_.geometry(); }
  const LocalCostmapParams& params() const { return params_; }

  // Recovery "clear costmaps": forget every obstacle.
  void clear();

 private:
  void recenter(const Pose2& T_map_base, Costmap2D& previous);

  LocalCostmapParams params_;
  ObstacleLayer obstacle_layer_;
  Inflator inflator_;
  Costmap2D layer_;
  Costmap2D obstacles_;
  Costmap2D costmap_;
  bool placed_ = false;
};

}  // namespace bipednav::mapping
