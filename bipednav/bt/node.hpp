#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bipednav/bt/blackboard.hpp"

namespace bipednav::bt {

enum class BtStatus { IDLE, RUNNING, SUCCESS, FAILURE };
std::string_view bt_status_name(BtStatus s);

enum class BtNodeKind { Action, Condition, Control, Decorator, SubTree };
std::string_view bt_kind_name(BtNodeKind k);

enum class BtPortDir { Input, Output };

// One declared port of a node type. Input ports without a default are required in the XML.
struct BtPortSpec {
  std::string name;
  BtPortDir dir = BtPortDir::Input;
  BtType type = BtType::Any;
  std::optional<std::string> default_value;  // literal or "{key}"

  static BtPortSpec input(std::string n, BtType t, std::optional<std::string> def = std::nullopt) {
    return {std::move(n), BtPortDir::Input, t, std::move(def)};
  }
  // Output ports default to the blackboard key of the same name ("{name}").
  static BtPortSpec output(std::string n, BtType t) {
    std::string def = "{" + n + "}";
    return {std::move(n), BtPortDir::Output, t, std::move(def)};
  }
};
using BtPorts = std::vector<BtPortSpec>;

// Called on every status change of every node (for logs, the HTML replay and the run figure).
class BtNode;
using BtObserver = std::function<void(const BtNode& node, BtStatus previous, BtStatus current, double now_s)>;

// Per-tree state the nodes share: the observer. Owned by the BehaviorTree.
struct BtTreeContext {
  BtObserver observer;
};

// Everything a node learns from the XML: its type ID, instance name, path in the tree,
// port values (attribute text, defaults filled in), the blackboard of its (sub)tree.
struct BtNodeConfig {
  std::string id;    // node type ("FollowPath", "Sequence")
  std::string name;  // the `name` attribute, else the ID
  std::string path;  // "Navigate/RestartOnGoalUpdate/.../FollowPath"
  std::string file;  // XML source and line, for messages
  int line = 0;
  std::map<std::string, std::string> ports;
  BtPorts port_specs;
  std::shared_ptr<Blackboard> blackboard;
  BtTreeContext* context = nullptr;
};

// Base of every node. Parents call execute_tick(); halt_node() stops a RUNNING node and
// leaves it IDLE. Subclasses implement tick() and, if they keep state across ticks, halt().
class BtNode {
 public:
  explicit BtNode(BtNodeConfig config) : config_(std::move(config)) {}
  virtual ~BtNode() = default;
  BtNode(const BtNode&) = delete;
  BtNode& operator=(const BtNode&) = delete;

  virtual BtNodeKind kind() const = 0;

  BtStatus execute_tick(double now_s);
  // Halts this node if RUNNING (recursively), then resets it to IDLE.
  void halt_node();

  BtStatus status() const { return status_; }
  // The last non-IDLE status tick() returned (kept after the parent resets the node).
  BtStatus last_result() const { return last_result_; }
  double last_tick_s() const { return last_tick_s_; }
  const BtNodeConfig& config() const { return config_; }
  const std::string& name() const { return config_.name; }
  const std::string& id() const { return config_.id; }
  const std::string& path() const { return config_.path; }
  const std::vector<std::unique_ptr<BtNode>>& children() const { return children_; }
  void add_child(std::unique_ptr<BtNode> child) { children_.push_back(std::move(child)); }

  // The input port's value: a literal converted to T, or the referenced blackboard entry.
  // nullopt when the port is unset or the blackboard key is absent; Error on a bad value.
  template <class T>
  std::optional<T> get_input(const std::string& port) const {
    auto v = input_value(port, bt_type<T>());
    if (!v) return std::nullopt;
    return std::get<T>(*v);
  }
  // Like get_input but throws Error naming the node and port when there is no value.
  template <class T>
  T input(const std::string& port) const {
    auto v = get_input<T>(port);
    if (!v) throw Error(describe() + ": input port '" + port + "' has no value");
    return *v;
  }
  // Writes the output port's blackboard entry (the port must reference "{key}").
  template <class T>
  void set_output(const std::string& port, T value) {
    write_output(port, BtValue(std::move(value)));
  }

  std::string describe() const;  // "FollowPath 'name' (file:line)"

 protected:
  virtual BtStatus tick(double now_s) = 0;
  // Called by halt_node() only while RUNNING; stop what the node started.
  virtual void halt() {}
  void halt_children();
  void halt_child(std::size_t i) { children_[i]->halt_node(); }
  BtNode& child(std::size_t i) { return *children_[i]; }
  std::size_t child_count() const { return children_.size(); }
  void set_status(BtStatus s, double now_s);

 private:
  std::optional<BtValue> input_value(const std::string& port, BtType type) const;
  void write_output(const std::string& port, BtValue value);

  BtNodeConfig config_;
  std::vector<std::unique_ptr<BtNode>> children_;
  BtStatus status_ = BtStatus::IDLE;
  BtStatus last_result_ = BtStatus::IDLE;
  double last_tick_s_ = 0.0;
};

// A synchronous check: SUCCESS when check() is true, FAILURE otherwise, never RUNNING.
class BtCondition : public BtNode {
 public:
  using BtNode::BtNode;
  BtNodeKind kind() const override { return BtNodeKind::Condition; }

 protected:
  virtual bool check(double now_s) = 0;
  BtStatus tick(double now_s) final { return check(now_s) ? BtStatus::SUCCESS : BtStatus::FAILURE; }
};

// A condition given as a function (convenient for bindings that just read the server).
class BtLambdaCondition final : public BtCondition {
 public:
  using Fn = std::function<bool(BtNode& self, double now_s)>;
  BtLambdaCondition(BtNodeConfig config, Fn fn) : BtCondition(std::move(config)), fn_(std::move(fn)) {}

 protected:
  bool check(double now_s) override { return fn_(*this, now_s); }

 private:
  Fn fn_;
};

// A long action spanning ticks (BehaviorTree.CPP's StatefulActionNode): on_start() on the
// first tick, on_running() on later ticks while RUNNING, on_halted() when preempted.
class BtStatefulAction : public BtNode {
 public:
  using BtNode::BtNode;
  BtNodeKind kind() const override { return BtNodeKind::Action; }

 protected:
  virtual BtStatus on_start(double now_s) = 0;
  virtual BtStatus on_running(double now_s) = 0;
  virtual void on_halted() = 0;

  BtStatus tick(double now_s) final;
  void halt() final { on_halted(); }
};

// A stateful action given as functions: `step(self, now_s, first)` is called with first=true
// on the tick that starts the action and false on later ticks while it is RUNNING;
// `halted(self)` when it is preempted (may be empty).
class BtLambdaAction final : public BtStatefulAction {
 public:
  using StepFn = std::function<BtStatus(BtNode& self, double now_s, bool first)>;
  using HaltFn = std::function<void(BtNode& self)>;
  BtLambdaAction(BtNodeConfig config, StepFn step, HaltFn halted)
      : BtStatefulAction(std::move(config)), step_(std::move(step)), halted_(std::move(halted)) {}

 protected:
  BtStatus on_start(double now_s) override { return step_(*this, now_s, true); }
  BtStatus on_running(double now_s) override { return step_(*this, now_s, false); }
  void on_halted() override {
    if (halted_) halted_(*this);
  }

 private:
  StepFn step_;
  HaltFn halted_;
};

// The literal value of a built-in node's parameter port (defaults already filled in).
// Throws FileError naming the XML line when it is missing or not a literal of `type`.
BtValue bt_literal_param(const BtNodeConfig& config, const std::string& port, BtType type);
// The same for an Int port.
int bt_int_param(const BtNodeConfig& config, const std::string& port);
// Throws FileError naming the node's XML line: a parameter that parsed but makes no sense.
[[noreturn]] void bt_param_error(const BtNodeConfig& config, const std::string& what);

// Delay's and Sleep's clock: simulated time counted from the first call of elapsed() after
// construction or restart(), read from the node's msec port (an int >= 0).
class BtSimTimer {
 public:
  BtSimTimer(const BtNodeConfig& config, const std::string& msec_port);
  bool elapsed(double now_s);
  void restart() { started_ = false; }

 private:
  double duration_s_ = 0.0;
  bool started_ = false;
  double start_s_ = 0.0;
};

}  // namespace bipednav::bt
