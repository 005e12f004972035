#include "bench/json_figures.hpp"

#include <cmath>

namespace bipednav::bench {

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace bipednav::bench
