#pragma once

#include <Eigen/Core>
#include <map>
#include <vector>

namespace bipednav::tracking {

// An object or a tracker's hypothesis of one at one evaluation time.
struct MotObject {
  int id = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  // A truth object whose velocity has jumped within the last moments (a simulated person turning
  // on the spot at a waypoint): no causal filter knows the new velocity yet, so its matches'
  // velocity errors are also summed apart (MotSummary::velocity_rmse_steady_mps). Hypotheses: unused.
  bool turning = false;
};

// The CLEAR MOT metrics (Bernardin and Stiefelhagen 2008) over a sequence of frames, with the
// position and velocity errors of the matched pairs and the time a tracker takes to pick up an
// object that comes into view.
struct MotSummary {
  long truths = 0;                                        // GT: truth objects summed over frames
  long matches = 0;                                       // TP
  long misses = 0;                                        // FN
  long false_positives = 0;                               // FP
  long id_switches = 0;                                   // IDSW
  double position_rmse_m = 0.0, velocity_rmse_mps = 0.0;  // over the matches
  // The matches on turning objects (MotObject::turning), and the velocity RMSE over the others.
  long matches_turning = 0;
  double velocity_rmse_steady_mps = 0.0;
  // Appearances: an object counted after not being counted for at least the gap (or for the first
  // time). Each is picked up at its first match; the delay from its start.
  long appearances = 0, appearances_picked_up = 0;
  double mean_pickup_s = 0.0, max_pickup_s = 0.0;
  double mota() const;  // 1 - (FN + FP + IDSW) / GT (1 without truths)
};

// The summary of several sequences taken as one: counts added, the RMSEs pooled over the matches,
// the mean pick-up delay over the picked-up appearances.
MotSummary pool(const std::vector<MotSummary>& parts);

class ClearMot {
 public:
  // match_distance_m: a hypothesis farther than this from an object is no match for it.
  // appearance_gap_s: an object not counted this long counts as newly in view when counted again.
  explicit ClearMot(double match_distance_m = 0.5, double appearance_gap_s = 1.0);

  // One frame at t_s: the objects that count (`truths`), those that do not count but may be
  // tracked (`ignored`: out of view, out of range; a hypothesis on one is neither a match nor a
  // false positive), and the tracker's hypotheses. Frames in time order. Each object keeps the
  // hypothesis it was matched with while that stays within match_distance_m (an identity
  // switch when it is matched with another one later); the others are matched by the Hungarian
  // method on the distances. A hypothesis left over is a false positive unless it lies within
  // match_distance_m of an ignored object, or its latest match was an object now ignored (a track
  // coasting on an object out of view: not scored until the object is seen again), or it lies
  // outside the evaluated region (`in_region`, per hypothesis; empty: all inside).
  void add_frame(double t_s, const std::vector<MotObject>& truths, const std::vector<MotObject>& ignored,
                 const std::vector<MotObject>& hypotheses, const std::vector<char>& in_region = {});
  MotSummary summary() const;

 private:
  // Matches rows (objects) to columns (hypotheses) within match_distance_m by least total
  // distance; already used hypotheses (used[j]) are skipped. Returns per object the hypothesis or -1.
  std::vector<int> match(const std::vector<MotObject>& objects, const std::vector<MotObject>& hypotheses,
                         const std::vector<char>& used) const;
  void count_pickup(int truth_id, double t_s, bool matched);

  double match_distance_m_, appearance_gap_s_;
  MotSummary sum_;
  double position_se_ = 0.0, velocity_se_ = 0.0, steady_se_ = 0.0, pickup_sum_s_ = 0.0;
  std::map<int, int> last_match_;  // object id -> hypothesis id of its latest match
  std::map<int, int> last_truth_;  // hypothesis id -> object id of its latest match
  struct Appearance {
    double start_s = 0.0, last_counted_s = 0.0;
    bool picked_up = false;
  };
  std::map<int, Appearance> appearance_;  // object id -> its current appearance
};

}  // namespace bipednav::tracking
