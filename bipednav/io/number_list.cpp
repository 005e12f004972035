#include "bipednav/io/number_list.hpp"

#include <cmath>
#include <sstream>

namespace bipednav::io {

std::vector<double> parse_number_list(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ',')) {
    try {
      std::size_t used = 0;
      const double x = std::stod(part, &used);
      if (used != part.size() || !std::isfinite(x)) return {};
      v.push_back(x);
    } catch (const std::exception&) {
      return {};
    }
  }
  return v;
}

}  // namespace bipednav::io
