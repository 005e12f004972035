#include "apps/cli_checks.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <sstream>

namespace bipednav::app {

namespace check {

namespace {

bool parse_double(const std::string& text, double& v) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE;
}

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A validator of finite numbers that also satisfy `ok`, described as "a finite number <what>".
CLI::Validator number_check(const std::function<bool(double)>& ok, const std::string& what) {
  return CLI::Validator(
      [ok, what](std::string& text) -> std::string {
        double v = 0.0;
        if (parse_double(text, v) && std::isfinite(v) && ok(v)) return {};
        return "expected a finite number" + what + ", got '" + text + "'";
      },
      "NUMBER" + what);
}

}  // namespace

CLI::Validator finite() {
  return number_check([](double) { return true; }, "");
}
CLI::Validator positive() {
  return number_check([](double v) { return v > 0.0; }, " > 0");
}
CLI::Validator non_negative() {
  return number_check([](double v) { return v >= 0.0; }, " >= 0");
}
CLI::Validator in_range(double lo, double hi) {
  return number_check([lo, hi](double v) { return v >= lo && v <= hi; },
                      " in [" + number_text(lo) + ", " + number_text(hi) + "]");
}
CLI::Validator open_range(double lo, double hi) {
  return number_check([lo, hi](double v) { return v > lo && v < hi; },
                      " in (" + number_text(lo) + ", " + number_text(hi) + ")");
}

CLI::Validator integer_in(long long lo, long long hi) {
  const std::string what = "a whole number " + (hi == std::numeric_limits<long long>::max()
                                                    ? ">= " + std::to_string(lo)
                                                    : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return CLI::Validator(
      [lo, hi, what](std::string& text) -> std::string {
        // Decimal only: strtoll's base 0 would read "010" as 8, and strtoull takes "-1" as 2^64 - 1.
        const std::size_t first = !text.empty() && text[0] == '-' ? 1 : 0;
        const bool digits = text.size() > first && text.find_first_not_of("0123456789", first) == std::string::npos;
        errno = 0;
        const long long v = digits ? std::strtoll(text.c_str(), nullptr, 10) : 0;
        if (digits && errno != ERANGE && v >= lo && v <= hi) return {};
        return "expected " + what + ", got '" + text + "'";
      },
      "INT");
}

CLI::Validator integer_at_least(long long min) { return integer_in(min, std::numeric_limits<long long>::max()); }

}  // namespace check

namespace {

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

}  // namespace

std::string flag_message(const ParamError& e, const FlagNames& names) {
  // ParamError's message is "invalid parameter '<field>': expected <what>" (common/error.hpp).
  const std::string what = e.what(), head = "invalid parameter '", sep = "': expected ";
  const std::size_t end = what.find(sep);
  if (what.rfind(head, 0) != 0 || end == std::string::npos) return {};
  const std::string field_name = what.substr(head.size(), end - head.size());
  std::string flag;
  for (const auto& [field, option] : names)
    if (field == field_name) flag = option;
  if (flag.empty()) return {};
  std::string expected = what.substr(end + sep.size());
  for (const auto& [field, option] : names) replace_all(expected, field, option);
  return flag + ": expected " + expected;
}

}  // namespace bipednav::app
