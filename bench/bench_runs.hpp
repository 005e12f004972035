#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/runner/scenario_runner.hpp"

namespace bipednav::bench {

// Calls work(i) for every i in [0, n), `jobs` at a time (the calling thread is one of them), with a
// progress bar labelled `label` counting finished items. Each item should catch its own errors.
void run_in_parallel(std::size_t n, int jobs, const std::string& label, const std::function<void(std::size_t)>& work);

// The median of v (0 when empty).
double median(std::vector<double> v);

// Each robot's profile by the name given (a profile file's robot by its path), after reading its
// navigation parameters with `base` (a bad parameters file is reported once, not as every run's error).
std::map<std::string, RobotProfile> robot_profiles(const std::vector<std::string>& robots,
                                                   const runner::RunOptions& base);

}  // namespace bipednav::bench
