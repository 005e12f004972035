#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bipednav/io/param_reader.hpp"

namespace bipednav::io {

// Overlays the mapping of `r` onto the struct `p` by its visit_fields (ParamOverlay), rejecting
// unknown keys (no validate(): the caller knows when its struct is complete).
template <class S>
void overlay_fields(ParamReader& r, S& p);

// Each parameter struct lists its fields once, in its own header, as a member
// `template <class V> void visit_fields(V& v)`: the visitor's operator()(key, field) takes scalars,
// strings and Eigen vectors, and group(key, nested_struct) a nested mapping. ParamOverlay is the
// visitor that reads: it sets the fields present in a mapping of `r` (nested structs from nested
// mappings), and the caller's r.finish() then rejects the keys no field asked for.
class ParamOverlay {
 public:
  explicit ParamOverlay(ParamReader& r) : r_(r) {}

  template <class T>
  void operator()(const char* key, T& value) {
    r_.get(key, value);
  }
  template <int N>
  void operator()(const char* key, Eigen::Matrix<double, N, 1>& value) {
    std::vector<double> xs;
    if (!r_.get(key, xs)) return;
    if (xs.size() != static_cast<std::size_t>(N)) r_.fail(key, "a list of " + std::to_string(N) + " numbers");
    for (int i = 0; i < N; ++i) value[i] = xs[static_cast<std::size_t>(i)];
  }
  template <class S>
  void group(const char* key, S& nested) {
    ParamReader child = r_.child(key);
    overlay_fields(child, nested);
  }

 private:
  ParamReader& r_;
};

template <class S>
void overlay_fields(ParamReader& r, S& p) {
  ParamOverlay overlay(r);
  p.visit_fields(overlay);
  r.finish();
}

}  // namespace bipednav::io
