#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace bipednav::bench {

struct HumanoidDriftOptions {
  std::string scenario = "nao_drift_walk";  // a footstep scenario: a name in scenarios/ or a file
};

// `bench localization`'s humanoid rows: the second reference's drift experiment (section VI, Fig. 7)
// in the simulator. A footstep run of the scenario; the planar and yaw drift per metre of the
// GICP-corrected estimate and of the leg odometry alone, against the reference's figures. Throws
// Error when the humanoid takes no step.
nlohmann::json bench_humanoid_drift(const HumanoidDriftOptions& options);

}  // namespace bipednav::bench
