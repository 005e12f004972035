#include "bipednav/io/param_reader.hpp"

namespace bipednav::io {

ParamReader::ParamReader(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (node_ && !node_.IsNull() && !node_.IsMap())
    throw FileError(file_, path_.empty() ? "<root>" : path_, "expected a mapping of key: value pairs");
}

ParamReader ParamReader::from_file(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw FileError(file.string(), "", "file not found");
  try {
    return ParamReader(YAML::LoadFile(file.string()), file.string());
  } catch (const YAML::Exception& e) {
    throw FileError(file.string(), "line " + std::to_string(e.mark.line + 1), "invalid YAML: " + e.msg);
  }
}

ParamReader ParamReader::from_string(const std::string& yaml, const std::string& name) {
  try {
    return ParamReader(YAML::Load(yaml), name);
  } catch (const YAML::Exception& e) {
    throw FileError(name, "line " + std::to_string(e.mark.line + 1), "invalid YAML: " + e.msg);
  }
}

ParamReader ParamReader::child(const std::string& key) {
  seen_.insert(key);
  return ParamReader(node_[key], file_, field_path(key));
}

std::vector<ParamReader> ParamReader::children(const std::string& key) {
  seen_.insert(key);
  std::vector<ParamReader> out;
  const YAML::Node n = node_[key];
  if (!n) return out;
  if (!n.IsSequence()) fail(key, "a list");
  for (std::size_t i = 0; i < n.size(); ++i)
    out.emplace_back(n[i], file_, field_path(key) + "[" + std::to_string(i) + "]");
  return out;
}

void ParamReader::finish() const {
  if (!node_ || !node_.IsMap()) return;
  for (const auto& kv : node_) {
    if (kv.first.IsSequence() ||
        kv.first.IsMap())  // "? [a, b]: 1" (a list or mapping as a key); found by fuzz_param_yaml
      throw FileError(file_,
                      "line " + std::to_string(kv.first.Mark().line + 1) + ": " + (path_.empty() ? "<root>" : path_),
                      "expected a plain key, found a list or mapping as a key");
    const std::string key = kv.first.as<std::string>();
    if (!seen_.count(key)) throw FileError(file_, field_path(key), "unknown parameter");
  }
}

void ParamReader::fail(const std::string& key, const std::string& expected) const {
  const YAML::Node n = node_[key];
  std::string where = field_path(key);
  if (n && n.Mark().line >= 0) where = "line " + std::to_string(n.Mark().line + 1) + ": " + where;
  throw FileError(file_, where, "expected " + expected);
}

}  // namespace bipednav::io
