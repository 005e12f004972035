#pragma once

#include <map>
#include <string>
#include <vector>

#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/viz/replay_html.hpp"

namespace bipednav::runner {

// Records a humanoid footstep run for the HTML replay (viz/replay_html.hpp, its footstep layer)
// through FootstepRunOptions::on_decision: one frame per step decision (true and estimated body,
// the plan's remaining feet, replans, the outcome), the navigator's Kalman heightmap whenever it
// changed, and at the end the feet actually taken.
class FootstepReplayRecorder {
 public:
  explicit FootstepReplayRecorder(const sim::Scenario& scenario);

  // The per-decision hook (FootstepRunOptions::on_decision).
  void record(const sim::HumanoidWalker& walker, const navigation::FootstepNavigator& nav,
              const navigation::StepDecision& decision);
  // Installs record() as options.on_decision (after any hook already there). The recorder must
  // outlive the run.
  void attach(FootstepRunOptions& options);

  const std::vector<viz::ReplayFrame>& frames() const { return data_.frames; }
  // The recording with the run's summary, the feet taken and the heightmaps (quantised over the
  // heights of all of them).
  viz::ReplayData finish(const FootstepRunResult& run) const;

 private:
  struct HeightSnapshot {
    double t_s = 0.0;
    mapping::GridGeometry geometry;
    std::vector<float> heights;
  };
  std::string kind_of(const std::string& action) const;  // the action's kind name (planar, step_over, ...)

  viz::ReplayData data_;
  Pose2 goal_;
  std::vector<HeightSnapshot> heights_;
  std::map<std::string, std::string> kinds_;  // action name -> kind name
};

}  // namespace bipednav::runner
