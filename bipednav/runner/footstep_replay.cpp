#include "bipednav/runner/footstep_replay.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "bipednav/runner/replay_recorder.hpp"

namespace bipednav::runner {

namespace {

viz::ReplayFoot replay_foot(const planning::footstep::Footstep& f, double t_s, std::string action) {
  return {t_s, f.foot == planning::footstep::Foot::kLeft, f.pose, std::move(action)};
}

bool same_heights(const std::vector<float>& a, const std::vector<float>& b) {  // bitwise: NaN marks unknown
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

FootstepReplayRecorder::FootstepReplayRecorder(const sim::Scenario& scenario)
    : data_(replay_scene(scenario)), goal_(scenario.goals.empty() ? Pose2{} : scenario.goals.back().pose) {
  data_.actors.clear();  // the footstep loop moves no actors
  // It walks to the last goal only (footstep_runner.hpp).
  if (data_.goals.size() > 1) data_.goals.erase(data_.goals.begin(), data_.goals.end() - 1);
  for (auto& g : data_.goals) g.t_s = 0.0;
}

void FootstepReplayRecorder::attach(FootstepRunOptions& options) {
  auto previous = std::move(options.on_decision);
  options.on_decision = [this, previous](const sim::HumanoidWalker& walker, const navigation::FootstepNavigator& nav,
                                         const navigation::StepDecision& d) {
    if (previous) previous(walker, nav, d);
    record(walker, nav, d);
  };
}

std::string FootstepReplayRecorder::kind_of(const std::string& action) const {
  const auto it = kinds_.find(action);
  return it == kinds_.end() ? action : it->second;
}

void FootstepReplayRecorder::record(const sim::HumanoidWalker& walker, const navigation::FootstepNavigator& nav,
                                    const navigation::StepDecision& d) {
  if (kinds_.empty())
    for (const auto& a : nav.planner().lattice().actions().actions)
      kinds_[a.name] = planning::footstep::action_kind_name(a.kind);
  const double t = walker.time_s();
  const auto& heights = nav.map().heights();
  if (heights_.empty() || !same_heights(heights_.back().heights, heights))
    heights_.push_back({t, nav.map().geometry(), heights});
  viz::ReplayFrame f;
  f.t_s = t;
  f.true_pose = walker.body_pose();
  f.estimated_pose = sim::body_between(nav.to_map(walker.odom_stance()).pose, nav.to_map(walker.odom_swing()).pose);
  f.goal = goal_;
  f.replanned = d.replanned;
  if (d.done) {
    f.state = d.result.ok() ? "SUCCEEDED" : "FAILED";
    f.outcome = std::string(outcome_name(d.result.outcome));
  } else {
    f.state = "ACTIVE";
    f.active_node = kind_of(d.action->name);
    const planning::footstep::FootstepPlan& plan = nav.plan();
    for (std::size_t j = nav.plan_cursor(); j < plan.steps.size(); ++j)
      f.plan.push_back(
          replay_foot(plan.steps[j], t, j > 0 && j - 1 < plan.actions.size() ? kind_of(plan.actions[j - 1]) : ""));
  }
  data_.frames.push_back(std::move(f));
}

viz::ReplayData FootstepReplayRecorder::finish(const FootstepRunResult& run) const {
  viz::ReplayData out = data_;
  out.summary = replay_summary(run.summary);
  out.robot_radius_m = run.body.arm_offset_m + run.body.arm_width_m / 2;
  viz::ReplayFootsteps fs;
  fs.foot_length_m = run.body.foot_length_m;
  fs.foot_width_m = run.body.foot_width_m;
  for (const auto& f : run.start_feet) fs.taken.push_back(replay_foot(f, 0.0, ""));
  for (const auto& s : run.steps) fs.taken.push_back(replay_foot(s.foot, s.t_s, kind_of(s.action)));
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (const auto& snapshot : heights_)
    for (const float h : snapshot.heights)
      if (std::isfinite(h)) lo = std::min(lo, h), hi = std::max(hi, h);
  if (!(lo <= hi)) lo = hi = 0.0f;
  fs.height_lo_m = lo;
  fs.height_hi_m = hi;
  for (const auto& snapshot : heights_) {
    const auto& g = snapshot.geometry;
    viz::ReplayGrid grid{snapshot.t_s, g.width, g.height, g.resolution_m, g.origin_x_m, g.origin_y_m, {}};
    grid.cells.reserve(snapshot.heights.size());
    for (const float h : snapshot.heights)
      grid.cells.push_back(!std::isfinite(h) ? 255
                           : hi > lo         ? static_cast<std::uint8_t>(std::lround(254.0 * (h - lo) / (hi - lo)))
                                             : 0);
    fs.height_maps.push_back(std::move(grid));
  }
  out.footsteps = std::move(fs);
  // The robot walked on after the last decision (a fall, the time limit): a last frame there.
  if (!run.steps.empty() && (out.frames.empty() || run.steps.back().t_s > out.frames.back().t_s + 1e-9)) {
    const ExecutedStep& s = run.steps.back();
    viz::ReplayFrame f;
    f.t_s = s.t_s;
    f.true_pose = s.body;
    f.estimated_pose = s.estimated_body;
    f.goal = goal_;
    f.state = run.summary.outcome.ok() ? "SUCCEEDED" : "FAILED";
    f.outcome = std::string(outcome_name(run.summary.outcome.outcome));
    out.frames.push_back(std::move(f));
  }
  return out;
}

}  // namespace bipednav::runner
