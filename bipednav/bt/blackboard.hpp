#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"

namespace bipednav::bt {

// The value types a blackboard entry or a port may hold.
using Value = std::variant<std::monostate, bool, int, double, std::string, Pose2, Path>;

enum class BtType { Any, Bool, Int, Double, String, Pose2, Path };

std::string_view bt_type_name(BtType t);
BtType bt_type_of(const Value& v);

template <class T>
constexpr BtType bt_type() {
  if constexpr (std::is_same_v<T, bool>)
    return BtType::Bool;
  else if constexpr (std::is_same_v<T, int>)
    return BtType::Int;
  else if constexpr (std::is_same_v<T, double>)
    return BtType::Double;
  else if constexpr (std::is_same_v<T, std::string>)
    return BtType::String;
  else if constexpr (std::is_same_v<T, Pose2>)
    return BtType::Pose2;
  else if constexpr (std::is_same_v<T, Path>)
    return BtType::Path;
  else
    static_assert(sizeof(T) == 0, "unsupported blackboard type");
}

// Parses a literal port value ("0.3", "true", "1;2;0.5" for a Pose2 as x;y;theta).
// Returns nullopt when `text` is not a valid literal of `type` (Path has no literal form).
std::optional<Value> bt_parse_literal(const std::string& text, BtType type);

// Converts `v` to `type`: identical types pass, strings are parsed, int widens to double.
// Throws Error naming `what` when the value cannot be converted.
Value bt_convert(const Value& v, BtType type, const std::string& what);

// True for a port value of the form "{key}"; `key` receives the key.
bool bt_is_reference(const std::string& port_value, std::string* key = nullptr);

// Typed key/value store shared by the nodes of one tree. A SubTree gets its own blackboard
// whose keys may be remapped to keys of the parent (explicit `port="{parent_key}"`) or,
// with autoremap, fall through to the parent under the same name (keys starting with '_'
// stay private, as in BehaviorTree.CPP v4).
class Blackboard {
 public:
  static std::shared_ptr<Blackboard> create(std::shared_ptr<Blackboard> parent = nullptr);

  // Writes `value`; an existing entry keeps its type (std::monostate entries take any type).
  void set_value(const std::string& key, Value value);
  template <class T>
  void set(const std::string& key, T value) {
    if constexpr (std::is_convertible_v<T, std::string> && !std::is_same_v<T, std::string>)
      set_value(key, Value(std::string(value)));
    else
      set_value(key, Value(std::move(value)));
  }

  // The raw entry after remapping, or nullptr when absent.
  const Value* find(const std::string& key) const;
  bool has(const std::string& key) const { return find(key) != nullptr; }
  void erase(const std::string& key);

  // The value converted to T; nullopt when absent; Error when it cannot be converted.
  template <class T>
  std::optional<T> get(const std::string& key) const {
    const Value* v = find(key);
    if (v == nullptr || std::holds_alternative<std::monostate>(*v)) return std::nullopt;
    return std::get<T>(bt_convert(*v, bt_type<T>(), "blackboard key '" + key + "'"));
  }

  // `key` of this blackboard refers to `parent_key` of the parent blackboard.
  void remap(const std::string& key, const std::string& parent_key);
  void set_autoremap(bool on) { autoremap_ = on; }
  const std::shared_ptr<Blackboard>& parent() const { return parent_; }

 private:
  explicit Blackboard(std::shared_ptr<Blackboard> parent) : parent_(std::move(parent)) {}
  // The blackboard and key an access to `key` lands on after remapping.
  std::pair<const Blackboard*, std::string> resolve(const std::string& key) const;

  std::shared_ptr<Blackboard> parent_;
  std::map<std::string, Value> entries_;
  std::map<std::string, std::string> remap_;
  bool autoremap_ = false;
};

}  // namespace bipednav::bt
