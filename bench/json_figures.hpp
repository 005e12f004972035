#pragma once

#include <nlohmann/json.hpp>

// Helpers of the benchmark harnesses' JSON figures (units in the key names: `_m`, `_s`, `_ms`, `_rad`).
namespace bipednav::bench {

// JSON has no infinity: a figure that is unbounded (a route without obstacles, a goal never
// reached) is null.
nlohmann::json finite_or_null(double v);

}  // namespace bipednav::bench
