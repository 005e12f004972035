#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "bipednav/common/error.hpp"

namespace bipednav::io {

// Reads YAML mappings into plain parameter structs. Keys are optional (the struct's in-class
// default stays), but a present key with the wrong type, or an unknown key, raises a FileError
// naming the file, the field's full path and what was expected.
//
//   ParamReader r = ParamReader::from_file("digit.yaml");
//   r.get("max_vel_x_mps", p.max_vel_x_mps);
//   r.finish();  // rejects keys nobody asked for
class ParamReader {
 public:
  ParamReader(YAML::Node node, std::string file, std::string path = "");
  static ParamReader from_file(const std::filesystem::path& file);
  static ParamReader from_string(const std::string& yaml, const std::string& name = "<string>");

  template <typename T>
  bool get(const std::string& key, T& out) {
    seen_.insert(key);
    const YAML::Node n = node_[key];
    if (!n) return false;
    try {
      out = n.as<T>();
    } catch (const YAML::Exception&) {
      fail(key, std::string("a value of type ") + type_name<T>());
    }
    return true;
  }

  // Like get(), but the key must be present.
  template <typename T>
  void require(const std::string& key, T& out) {
    if (!get(key, out)) fail(key, "this required key to be present");
  }

  bool has(const std::string& key) const { return static_cast<bool>(node_[key]); }
  // A nested mapping; an absent key gives an empty reader.
  ParamReader child(const std::string& key);
  // The elements of a sequence, each as a reader (absent key: empty list).
  std::vector<ParamReader> children(const std::string& key);
  // Rejects keys in this mapping that no get()/child() call asked for.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;
  const YAML::Node& node() const { return node_; }
  const std::string& file() const { return file_; }
  std::string field_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

 private:
  template <typename T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, bool>)
      return "bool";
    else if constexpr (std::is_integral_v<T>)
      return "integer";
    else if constexpr (std::is_floating_point_v<T>)
      return "number";
    else if constexpr (std::is_same_v<T, std::string>)
      return "string";
    else
      return "list";
  }

  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::set<std::string> seen_;
};

}  // namespace bipednav::io
