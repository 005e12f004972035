#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bipednav/common/error.hpp"

// Checks of numeric option values shared by every command. CLI11 runs them on the text before
// converting it and prefixes their message with the option's name, so a bad value is reported as
// "--time-limit: expected a finite number > 0, got '-5'" (exit 2). CLI11's own PositiveNumber and
// Range let NaN through; these do not.
namespace bipednav::app::check {

// A finite number (any sign): heights, coordinates.
CLI::Validator finite();
// A finite number > 0: times, distances, sizes.
CLI::Validator positive();
// A finite number >= 0 (0 has a documented meaning, e.g. "no voxel grid").
CLI::Validator non_negative();
// A finite number in [lo, hi].
CLI::Validator in_range(double lo, double hi);
// A finite number in (lo, hi) (e.g. a probability strictly between 0 and 1).
CLI::Validator open_range(double lo, double hi);
// A whole number >= min (decimal digits, a sign only on a negative number): counts, seeds.
CLI::Validator integer_at_least(long long min);
// A whole number in [lo, hi].
CLI::Validator integer_in(long long lo, long long hi);

}  // namespace bipednav::app::check

namespace bipednav::app {

// Which option sets which parameter-struct field, to report a ParamError under the option's name.
using FlagNames = std::vector<std::pair<std::string, std::string>>;  // {field, --flag}

// Runs `f` (which fills a parameter struct from options and validates it); a ParamError about a
// field in `names` is rethrown as an Error naming the option ("--zmin: expected <= --zmax").
template <class F>
void with_flag_names(const FlagNames& names, F&& f);

// The message of `e` with the fields in `names` replaced by their options (empty: not one of them).
std::string flag_message(const ParamError& e, const FlagNames& names);

template <class F>
void with_flag_names(const FlagNames& names, F&& f) {
  try {
    f();
  } catch (const ParamError& e) {
    const std::string m = flag_message(e, names);
    if (m.empty()) throw;
    throw Error(m);
  }
}

}  // namespace bipednav::app
