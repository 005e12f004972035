#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "bipednav/planning/local/teb_band.hpp"
#include "bipednav/planning/local/teb_optimizer.hpp"
#include "bipednav/planning/local/teb_params.hpp"
#include "bipednav/planning/local/thread_pool.hpp"

namespace bipednav::planning::local {

// H-signature of a polyline in the winding-number form: for each obstacle centroid, the angle the
// path sweeps around it. Two paths with the same end points are homotopic (with respect to the
// centroids) iff every component agrees; otherwise some component differs by a multiple of 2 pi.
std::vector<double> winding_signature(const std::vector<Eigen::Vector2d>& path,
                                      const std::vector<Eigen::Vector2d>& centroids);
bool same_homotopy_class(const std::vector<double>& a, const std::vector<double>& b, double tolerance_rad);

// Distance between the segment a-b and an obstacle (0 when they intersect).
double segment_obstacle_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Obstacle& o);

// Candidate paths start -> goal through keypoints left and right of the obstacles near the
// start-goal line (a sparse roadmap whose edges only advance towards the goal and keep
// min_dist_m from every obstacle), enumerated shortest first, one per homotopy class, skipping the
// classes in `known` (signatures over `centroids`). Returns at most max_new paths (each including
// start and goal).
std::vector<std::vector<Eigen::Vector2d>> candidate_paths(const Pose2& start, const Pose2& goal,
                                                          const std::vector<Obstacle>& obstacles,
                                                          const std::vector<Eigen::Vector2d>& centroids,
                                                          double min_dist_m,
                                                          const std::vector<std::vector<double>>& known, int max_new,
                                                          const HomotopyParams& params);

// One candidate trajectory and its outcome in the current cycle.
struct BandCandidate {
  std::uint64_t id = 0;
  TebBand band;
  BandCost cost;
  bool ok = false;
};

// Keeps up to max_classes bands in distinct homotopy classes across cycles, optimises them in
// parallel and selects the cheapest, preferring the previous choice by selection_hysteresis.
// Deterministic for any thread count: every band is optimised independently into its own slot.
class HomotopyPlanner {
 public:
  explicit HomotopyPlanner(const TebParams& params);

  // Returns the selected candidate, or nullptr when no band could be optimised.
  const BandCandidate* plan(const Pose2& start, const Pose2& goal, const Twist& start_velocity,
                            const std::vector<Eigen::Vector2d>& via_points, const std::vector<Obstacle>& obstacles);
  void reset();
  const std::vector<BandCandidate>& candidates() const { return bands_; }
  // The moving obstacles the next plan()s optimise against (with TebOptimizerParams::dynamic_obstacles;
  // positions at the time of the band's start).
  void set_moving_obstacles(std::vector<TebMovingObstacle> moving) { moving_ = std::move(moving); }

 private:
  // warm_start leaves the kept bands' winding signatures in `signatures` (one per band, in order) when
  // it computed them (two bands or more), else empties it; add_candidates uses them when given.
  void warm_start(const Pose2& start, const Pose2& goal, const std::vector<Eigen::Vector2d>& centroids,
                  std::vector<std::vector<double>>& signatures);
  void add_candidates(const Pose2& start, const Pose2& goal, const std::vector<Eigen::Vector2d>& via,
                      const std::vector<Obstacle>& obstacles, const std::vector<Eigen::Vector2d>& centroids,
                      std::vector<std::vector<double>>* signatures = nullptr);
  void optimise_all(const Twist& v0, const std::vector<Eigen::Vector2d>& via, const std::vector<Obstacle>& obstacles);
  // With `kept` (and not by_cost): the kept bands' signatures in band order, or empty when there was
  // nothing to compare (fewer than two bands).
  void drop_duplicates(const std::vector<Eigen::Vector2d>& centroids, bool by_cost,
                       std::vector<std::vector<double>>* kept = nullptr);
  const BandCandidate* select();

  TebParams params_;
  ThreadPool pool_;
  std::vector<BandCandidate> bands_;
  std::vector<TebMovingObstacle> moving_;
  std::uint64_t next_id_ = 1;
  std::uint64_t selected_id_ = 0;
};

}  // namespace bipednav::planning::local
