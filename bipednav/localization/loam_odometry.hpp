#pragma once

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/localization/feature_association.hpp"
#include "bipednav/localization/loam_features.hpp"
#include "bipednav/localization/point_kdtree.hpp"
#include "bipednav/localization/registration_lm.hpp"

namespace bipednav::localization {

// LiDAR odometry of LOAM (section 4.4.2-4.4.3, Algorithm 1).
struct OdometryParams {
  double scan_period_s = 0.1;  // t - t_{k+1}: the duration of one sweep
  AssociationParams association{};
  int correspondence_rounds = 6;  // re-associations (Algorithm 1, line 5)
  double relaxation = 0.5;        // fraction of each round's update applied (damps the reference loop)
  // The rounds stop once a round's applied change is below both of these (Algorithm 1's convergence
  // test). With the relaxation the change only halves per round: in the closed loop (turtlebot3,
  // hexagon_static) the median change is 5e-3 m in round 1, 4.5e-4 m in round 3 and 9e-5 m in round 5,
  // so the defaults run nearly all rounds. 1e-3 m / 3e-4 rad stop after ~3 rounds: the association
  // (re-projecting the reference and searching it) is ~40 % of LOAM's CPU, the rounds' LM ~10 %.
  double round_converged_translation_m = 1e-4;
  double round_converged_rotation_rad = 1e-5;
  std::size_t min_constraints = 20;  // fewer rows than this: the sweep is not matched
  LmParams lm{};
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("scan_period_s", scan_period_s);
    v.group("association", association);
    v("correspondence_rounds", correspondence_rounds);
    v("relaxation", relaxation);
    v("round_converged_translation_m", round_converged_translation_m);
    v("round_converged_rotation_rad", round_converged_rotation_rad);
    v("min_constraints", min_constraints);
    v.group("lm", lm);
  }
};

struct OdometryResult {
  SE3 T_start_end = SE3::Identity();  // LiDAR pose at the sweep end in the frame at its start
  bool matched = false;               // false: no reference or too few correspondences (guess kept)
  int degenerate_dims = 0;            // directions left at the guess (eigenvalue test)
  std::size_t constraints = 0;
  std::size_t inliers = 0;
  double rms_m = 0.0;
  int iterations = 0;  // LM iterations of all rounds
  int rounds = 0;      // correspondence rounds run
};

// Fraction of the sweep elapsed when point i was measured, (t_i - t_{k+1}) / (t - t_{k+1}) of eq. 4.8,
// clamped to [0, 1] (1 when the cloud carries no times: it is taken as already de-skewed).
double time_fraction(const PointCloud& c, std::size_t i, double scan_period_s);

// Moves every point to the LiDAR frame at the sweep end with the interpolated motion
// (eq. 4.8-4.10; Algorithm 1, line 15). Other fields are kept; time offsets are kept as measured.
PointCloud deskew_to_end(const PointCloud& cloud, const SE3& T_start_end, double scan_period_s);
// deskew_to_end's points only, into `out` (resized to the cloud's size; its capacity is reused).
void deskew_points_to_end(const PointCloud& cloud, const SE3& T_start_end, double scan_period_s,
                          std::vector<Eigen::Vector3f>& out);

class LoamOdometry {
 public:
  explicit LoamOdometry(OdometryParams p);

  // Motion over the sweep whose features are `f`, starting from `guess`. Degenerate directions
  // stay at the guess. Does not change the reference.
  //
  // The previous sweep is projected to its end (= this sweep's start) with the motion being
  // estimated (constant velocity over the two sweeps), re-projected every correspondence round.
  // Projecting it with its own earlier estimate instead closes a loop through the sweeps: an error
  // e in one estimate distorts the reference and returns as about -0.85 e in the next (the walls
  // behind the LiDAR are seen mid-sweep), which rings and, for the weakly observed roll and pitch,
  // grows.
  // `reference_offset` is the reference sweep's motion minus this sweep's (motion vectors of
  // se3_to_motion), e.g. from wheel odometry: the reference is projected with x + offset. Constant
  // velocity (zero) is wrong while the robot accelerates: turning up to 1.4 rad/s, the reference
  // was projected with a rotation ~0.03 rad per sweep too large, which returned as an estimate
  // ~0.01 rad (7 %) too small, corrected by the next mapping step in a jump (the opposite when
  // slowing down). The difference of two consecutive odometry motions is accurate even when the
  // odometry's scale is not, and no estimate of this class enters it (the loop above stays open).
  OdometryResult estimate(const LoamFeatures& f, const SE3& guess, const Vector6d& reference_offset = Vector6d::Zero());
  // Makes this sweep the reference for the next one; T_start_end is its estimated motion.
  void set_reference(const LoamFeatures& f, const SE3& T_start_end);
  bool has_reference() const { return !raw_edges_.empty() || !raw_planars_.empty(); }
  // The reference sweep's map features, de-skewed to its end (the mapping step's input). De-skewed
  // on the first call after set_reference: the mapping step reads them on one sweep in ten.
  const PointCloud& reference_edges() const;
  const PointCloud& reference_planars() const;
  void reset();
  const OdometryParams& params() const { return p_; }

 private:
  std::vector<Constraint> associate(const LoamFeatures& f, const Vector6d& x, const Vector6d& reference_offset);

  void deskew_reference() const;

  // The reference's features de-skewed with the motion being estimated, and a kd-tree over them.
  // The tree is rebuilt only when a point moved more than kRebuildM since it was built: neighbours
  // are searched among the tree's positions and fitted at the current ones.
  struct MovingReference {
    static constexpr float kRebuildM = 0.05f;
    PointKdTree tree;
    std::vector<Eigen::Vector3f> positions;
    void update(const PointCloud& raw, const SE3& T, double scan_period_s);
    MovedPoints points() const { return {&tree, &positions}; }
  };
  // associate()'s work space, kept between calls (rounds and sweeps; reset() keeps it too): a tree
  // is reused only while update() finds every point within kRebuildM of where the tree has it,
  // whatever cloud it was built from. Each feature's neighbours of the previous round (or sweep)
  // bound its next search (any neighbours do: see NeighbourHint; the matches do not depend on them).
  struct Workspace {
    MovingReference edges, planars;
    std::vector<NeighbourHint> edge_hints, planar_hints;
  };

  OdometryParams p_;
  PointCloud raw_edges_, raw_planars_;  // the previous sweep's map features, as measured
  SE3 raw_motion_ = SE3::Identity();    // their sweep's estimated motion
  // The same, de-skewed to its end with raw_motion_ (computed on demand: stale while ref_stale_).
  mutable PointCloud ref_edges_, ref_planars_;
  mutable bool ref_stale_ = false;
  Workspace work_;
};

}  // namespace bipednav::localization
