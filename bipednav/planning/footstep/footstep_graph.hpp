#pragma once

#include <memory>
#include <vector>

#include "bipednav/planning/footstep/ara_star.hpp"
#include "bipednav/planning/footstep/footstep_types.hpp"
#include "bipednav/planning/footstep/heuristics.hpp"
#include "bipednav/planning/footstep/inverse_heightmap.hpp"

namespace bipednav::planning::footstep {

// Precomputed, position-independent lattice data of an action set: for each stance foot,
// action and stance heading bin, the lattice displacement of the landing foot and its aligned
// inverse heightmap; for each heading bin the sole's cells. Built once per robot and lattice.
class ActionLattice {
 public:
  // `landing_margin_m`: a landed sole must also keep this far from any rising edge (a cell
  // higher than its top by more than the flatness threshold), so that the walker's landing
  // error does not put its toe on a riser. Edges that drop away need none: an overhang of a
  // centimetre or two still supports the sole.
  ActionLattice(const ActionSet& actions, double res, int theta_bins, double landing_margin_m = 0.0);

  struct Transition {
    int dix = 0, diy = 0, ditheta = 0;
  };
  const ActionSet& actions() const { return actions_; }
  double resolution_m() const { return res_; }
  int theta_bins() const { return bins_; }
  double theta_of(int itheta) const;
  int bin_of(double theta) const;
  const Transition& transition(Foot f, int action, int itheta) const { return trans_[slot(f, action, itheta)]; }
  const InverseHeightmap& ihm(Foot f, int action, int itheta) const { return ihm_[slot(f, action, itheta)]; }
  const std::vector<std::pair<std::int16_t, std::int16_t>>& sole(int itheta) const { return soles_[itheta]; }
  int sole_radius_cells() const { return sole_radius_; }
  // The cells within the landing margin around the sole (none without a margin).
  const std::vector<std::pair<std::int16_t, std::int16_t>>& margin_ring(int itheta) const { return rings_[itheta]; }
  int ring_radius_cells() const { return ring_radius_; }
  double landing_margin_m() const { return margin_m_; }

 private:
  std::size_t slot(Foot f, int a, int t) const {
    return (static_cast<std::size_t>(f) * actions_.actions.size() + a) * bins_ + t;
  }
  ActionSet actions_;
  double res_;
  int bins_;
  std::vector<Transition> trans_;
  std::vector<InverseHeightmap> ihm_;
  std::vector<std::vector<std::pair<std::int16_t, std::int16_t>>> soles_, rings_;
  int sole_radius_ = 0, ring_radius_ = 0;
  double margin_m_ = 0.0;
};

struct FootstepGoal {
  Pose2 body;
  double tolerance_m = 0.05;
  double tolerance_rad = 0.3;
};

// The footstep search space on a terrain: states are lattice keys, edges are the safe actions
// of section V-B (flat footprint, dz within the action's interval (eq. 4), whole-body check
// against the inverse heightmap (eq. 5)), costs are action durations. The heuristic is the
// larger of the position heuristic (eq. 6) and the time the heading needs to come within the
// goal's tolerance at the fastest turn per action: both are lower bounds of the remaining time,
// so their maximum is too, and the search no longer has to flood the goal's surroundings with
// every heading the position heuristic cannot tell apart.
//
// A state carries only its stance foot: the swing foot is assumed at the stance height, at the
// via point beside it. The start state is where the robot really stands (its own inverse
// heightmaps, built on first use): its stance foot has landed, so its lift-off needs no margin
// for a landing error (build_inverse_heightmap's stance_landed), and its swing foot may stand
// higher (the trailing foot still on the step the stance foot came down from) and keep that
// height until it drops onto its landing: the first action's downward phase is checked
// `start_swing_lift_m` higher. Lifts of at most kMinSwingLiftM count as none.
class FootstepGraph : public SearchGraph {
 public:
  static constexpr double kMinSwingLiftM = 1e-3;
  FootstepGraph(const ActionLattice& lattice, const TerrainGrid& terrain, const Heuristic& heuristic,
                const FootstepGoal& goal, const Footstep& start, double start_swing_lift_m = 0.0);

  std::int32_t start_state() override { return start_; }
  void successors(std::int32_t s, std::vector<Edge>& out) override;
  double heuristic(std::int32_t s) override;
  bool is_goal(std::int32_t s) override;

  const StateKey& key(std::int32_t s) const { return states_[s].key; }
  Footstep footstep(std::int32_t s) const;
  Pose2 body_centre(std::int32_t s) const;
  // Whether action `a` from state `s` is safe (for validating a plan against a newer map).
  bool action_safe(std::int32_t s, int a, std::int32_t* to = nullptr);

 private:
  struct State {
    StateKey key;
    float z = 0.0f;
    std::int8_t goal = -1;  // is_goal, once asked (-1: not yet)
  };
  // Packed state key -> state id for keys off the terrain grid (at most the start): open
  // addressing with linear probing.
  class StateIndex {
   public:
    StateIndex();
    // The id stored for `key`, or `fresh_id` (stored, *fresh = true) when the key is new.
    std::int32_t find_or_insert(std::uint64_t key, std::int32_t fresh_id, bool* fresh);

   private:
    struct Slot {
      std::uint64_t key_plus_one = 0;  // 0: empty
      std::int32_t id = -1;
    };
    std::size_t home(std::uint64_t key) const { return (key * 0x9E3779B97F4A7C15ull) >> shift_; }
    void grow();
    std::vector<Slot> slots_;
    std::size_t used_ = 0;
    int shift_ = 0;
  };
  // What landing_at found for a sole on (cell, heading): it does not depend on the
  // stance height except on wholly unknown ground, where the sole continues the stance height.
  enum class Landing : std::uint8_t { kUnasked = 0, kUnsafe, kAt, kStanceHeight };
  struct LandingCache {
    float z = 0.0f;
    Landing kind = Landing::kUnasked;
  };
  // Per terrain cell that any state reached: a block with the ids of its (heading, foot) states
  // and its landings by heading. A state's successors land on a few dozen nearby cells, so the
  // blocks stay in cache where a hash of the packed key would scatter (the hash lookup was a
  // quarter of the search time), and each landing is checked once instead of once per
  // predecessor.
  std::size_t block_of(int ix, int iy);
  std::int32_t intern(const StateKey& k, float z);
  // Whether a sole on (cell, heading) lands safely (flat, clear of rising edges) and its height
  // (*z, unless kStanceHeight).
  Landing landing_at(int ix, int iy, int itheta, float* z) const;
  // landing_at through the cell's landing cache, at `stance_z` on unknown ground.
  bool landing_height(int ix, int iy, int itheta, float stance_z, float* z);
  bool clear_of_rising_edges(int ix, int iy, int itheta, float top) const;  // the landing margin
  bool whole_body_free(const StateKey& s, float z, const InverseHeightmap& ihm) const;
  // The start state's inverse heightmap of action `a` (built on first use).
  const InverseHeightmap& start_ihm(int a);
  Pose2 pose_of(const StateKey& k) const;

  const ActionLattice& lattice_;
  const TerrainGrid& terrain_;
  const Heuristic& heuristic_;
  FootstepGoal goal_;
  std::vector<State> states_;
  StateIndex index_;
  std::vector<std::int32_t> cell_block_;  // per terrain cell: its block, -1 = none yet
  // Blocks live in fixed chunks: a growing vector would copy them and fault its fresh pages
  // in again at each doubling, which made the first iterations slower than the hash.
  static constexpr int kChunkShift = 6;         // 64 blocks per chunk
  std::int32_t* block_ids(std::size_t b);       // 2 * theta_bins state ids (-1 = none)
  LandingCache* block_landings(std::size_t b);  // theta_bins landings
  std::vector<std::unique_ptr<std::int32_t[]>> id_chunks_;
  std::vector<std::unique_ptr<LandingCache[]>> landing_chunks_;
  std::size_t blocks_ = 0;
  // Per (heading bin, stance foot): the body centre's offset from the stance foot, the same
  // products Pose2's composition forms, and the composed heading.
  std::vector<double> centre_dx_, centre_dy_, centre_theta_;
  std::int32_t start_ = 0;
  double start_lift_m_ = 0.0;  // > kMinSwingLiftM, or 0
  std::vector<InverseHeightmap> start_ihm_;
  std::vector<bool> start_ihm_built_;
  // Heading term of the heuristic: the most heading bins one action turns, the shortest action.
  int max_turn_bins_ = 0;
  double min_duration_s_ = 0.0;
};

}  // namespace bipednav::planning::footstep
