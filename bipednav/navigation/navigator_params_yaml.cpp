#include "bipednav/navigation/navigator_params_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <type_traits>

#include "bipednav/io/param_overlay.hpp"

namespace bipednav::navigation {

namespace {

// The fields each parameter struct lists in its visit_fields are read by io::ParamOverlay and
// written by ParamDump, so the two cannot disagree.

// The shortest text that reads back as the same double, with a ".0" on whole numbers so that the
// value is visibly a number of type double (YAML's .nan / .inf for non-finite values).
std::string double_text(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0.0 ? ".inf" : "-.inf";
  char buf[64];
  const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  std::string s(buf, end);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

class ParamDump {
 public:
  explicit ParamDump(YAML::Emitter& out) : out_(out) {}

  template <class T>
  void operator()(const char* key, const T& value) {
    out_ << YAML::Key << key << YAML::Value;
    if constexpr (std::is_floating_point_v<T>)
      out_ << double_text(value);
    else
      out_ << value;  // bool, integers, strings
  }
  template <int N>
  void operator()(const char* key, const Eigen::Matrix<double, N, 1>& value) {
    out_ << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int i = 0; i < N; ++i) out_ << double_text(value[i]);
    out_ << YAML::EndSeq;
  }
  template <class S>
  void group(const char* key, S& nested) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    nested.visit_fields(*this);
    out_ << YAML::EndMap;
  }

 private:
  YAML::Emitter& out_;
};

// The two top-level structs (NavigatorParams, FootstepNavigatorParams) are read and dumped alike.
template <class P>
void overlay_and_validate(io::ParamReader& r, P& p) {
  io::overlay_fields(r, p);
  try {
    p.validate();
  } catch (const ParamError& e) {  // validate() names the field, not the file
    throw FileError(r.file(), "", e.what());
  }
}

template <class P>
void overlay_file(const std::filesystem::path& file, P& p) {
  io::ParamReader r = io::ParamReader::from_file(file);
  overlay_and_validate(r, p);
}

template <class P>
std::string dump_params_yaml(const P& p) {
  P fields = p;  // the visitors take non-const fields (the reader writes them)
  YAML::Emitter out;
  out << YAML::BeginMap;
  ParamDump dump(out);
  fields.visit_fields(dump);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

void read_navigator_params(io::ParamReader& r, NavigatorParams& p) { overlay_and_validate(r, p); }
void read_navigator_params(io::ParamReader& r, FootstepNavigatorParams& p) { overlay_and_validate(r, p); }

void apply_navigator_params_file(const std::filesystem::path& file, NavigatorParams& p) { overlay_file(file, p); }
void apply_navigator_params_file(const std::filesystem::path& file, FootstepNavigatorParams& p) {
  overlay_file(file, p);
}

std::string navigator_params_yaml(const NavigatorParams& p) { return dump_params_yaml(p); }
std::string navigator_params_yaml(const FootstepNavigatorParams& p) { return dump_params_yaml(p); }

}  // namespace bipednav::navigation
