#pragma once

#include <string>
#include <vector>

namespace bipednav::io {

// Comma-separated finite numbers ("0.9,-1.5,0"); empty for anything else (a malformed or
// non-finite entry, an empty text), so callers name the field and say what they expected.
std::vector<double> parse_number_list(const std::string& text);

}  // namespace bipednav::io
