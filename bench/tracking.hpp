#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/tracking_harness.hpp"
#include "bipednav/sim/scenario.hpp"

namespace bipednav::bench {

// `bipednav bench tracking`: every scenario with every robot and seed (run_tracking), scored for
// the variants and the navigator's own tracker; one JSON object with the scores pooled per tracker
// (and the goals met or not) and each run's. Any list of scenarios (files, generated worlds).
nlohmann::json bench_tracking(const std::vector<sim::Scenario>& scenarios, const std::vector<std::string>& robots,
                              const std::vector<std::uint64_t>& seeds, const std::vector<TrackerVariant>& variants,
                              bool progress);

}  // namespace bipednav::bench
