#include "bipednav/bt/blackboard.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace bipednav::bt {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::optional<double> parse_double(const std::string& raw) {
  const std::string s = trim(raw);
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<int> parse_int(const std::string& raw) {
  const std::string s = trim(raw);
  int v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<bool> parse_bool(const std::string& raw) {
  std::string s = trim(raw);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (s == "true" || s == "1") return true;
  if (s == "false" || s == "0") return false;
  return std::nullopt;
}

// "x;y;theta" (BehaviorTree.CPP's convention) or "x,y,theta".
std::optional<Pose2> parse_pose(const std::string& s) {
  const char sep = s.find(';') != std::string::npos ? ';' : ',';
  std::vector<double> v;
  std::size_t start = 0;
  while (true) {
    const auto pos = s.find(sep, start);
    const auto d = parse_double(s.substr(start, pos == std::string::npos ? std::string::npos : pos - start));
    if (!d) return std::nullopt;
    v.push_back(*d);
    if (pos == std::string::npos) break;
    start = pos + 1;
  }
  if (v.size() != 3) return std::nullopt;
  return Pose2{v[0], v[1], v[2]};
}

}  // namespace

std::string_view bt_type_name(BtType t) {
  switch (t) {
    case BtType::Any:
      return "any";
    case BtType::Bool:
      return "bool";
    case BtType::Int:
      return "int";
    case BtType::Double:
      return "double";
    case BtType::String:
      return "string";
    case BtType::Pose2:
      return "Pose2";
    case BtType::Path:
      return "Path";
  }
  return "?";
}

BtType bt_type_of(const Value& v) {
  static constexpr BtType kTypes[] = {BtType::Any,    BtType::Bool,  BtType::Int, BtType::Double,
                                      BtType::String, BtType::Pose2, BtType::Path};
  return kTypes[v.index()];
}

std::optional<Value> bt_parse_literal(const std::string& text, BtType type) {
  switch (type) {
    case BtType::Any:
    case BtType::String:
      return Value(text);
    case BtType::Bool:
      if (auto b = parse_bool(text)) return Value(*b);
      return std::nullopt;
    case BtType::Int:
      if (auto i = parse_int(text)) return Value(*i);
      return std::nullopt;
    case BtType::Double:
      if (auto d = parse_double(text)) return Value(*d);
      return std::nullopt;
    case BtType::Pose2:
      if (auto p = parse_pose(text)) return Value(*p);
      return std::nullopt;
    case BtType::Path:
      return std::nullopt;
  }
  return std::nullopt;
}

Value bt_convert(const Value& v, BtType type, const std::string& what) {
  const BtType have = bt_type_of(v);
  if (have == type || type == BtType::Any) return v;
  if (have == BtType::Int && type == BtType::Double) return Value(static_cast<double>(std::get<int>(v)));
  if (have == BtType::String) {
    if (auto parsed = bt_parse_literal(std::get<std::string>(v), type)) return *parsed;
    throw Error(what + ": cannot convert \"" + std::get<std::string>(v) + "\" to " + std::string(bt_type_name(type)));
  }
  throw Error(what + " holds a " + std::string(bt_type_name(have)) + ", expected " + std::string(bt_type_name(type)));
}

bool bt_is_reference(const std::string& port_value, std::string* key) {
  const std::string s = trim(port_value);
  if (s.size() < 3 || s.front() != '{' || s.back() != '}') return false;
  if (key != nullptr) *key = s.substr(1, s.size() - 2);
  return true;
}

std::shared_ptr<Blackboard> Blackboard::create(std::shared_ptr<Blackboard> parent) {
  return std::shared_ptr<Blackboard>(new Blackboard(std::move(parent)));
}

std::pair<const Blackboard*, std::string> Blackboard::resolve(const std::string& key) const {
  if (auto it = remap_.find(key); it != remap_.end() && parent_) return parent_->resolve(it->second);
  if (entries_.count(key) != 0) return {this, key};
  if (autoremap_ && parent_ && !key.empty() && key.front() != '_') return parent_->resolve(key);
  return {this, key};
}

void Blackboard::set_value(const std::string& key, Value value) {
  const auto [bb_const, k] = resolve(key);
  auto* bb = const_cast<Blackboard*>(bb_const);  // resolve only walks blackboards this one owns a path to
  auto it = bb->entries_.find(k);
  if (it == bb->entries_.end() || std::holds_alternative<std::monostate>(it->second)) {
    bb->entries_[k] = std::move(value);
    return;
  }
  if (it->second.index() != value.index() && !std::holds_alternative<std::monostate>(value))
    throw Error("blackboard key '" + key + "' holds a " + std::string(bt_type_name(bt_type_of(it->second))) +
                ", cannot store a " + std::string(bt_type_name(bt_type_of(value))));
  it->second = std::move(value);
}

const Value* Blackboard::find(const std::string& key) const {
  const auto [bb, k] = resolve(key);
  const auto it = bb->entries_.find(k);
  return it == bb->entries_.end() ? nullptr : &it->second;
}

void Blackboard::erase(const std::string& key) {
  const auto [bb, k] = resolve(key);
  const_cast<Blackboard*>(bb)->entries_.erase(k);
}

void Blackboard::remap(const std::string& key, const std::string& parent_key) { remap_[key] = parent_key; }

}  // namespace bipednav::bt
