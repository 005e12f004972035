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

enum class Status { IDLE, RUNNING, SUCCESS, FAILURE };
std::string_view bt_status_name(Status s);

enum class NodeKind { Action, Condition, Control, Decorator, SubTree };
std::string_view bt_kind_name(NodeKind k);

enum class PortDir { Input, Output };

// One declared port of a node type. Input ports without a default are required in the XML.
struct PortSpec {
  std::string name;
  PortDir dir = PortDir::Input;
  BtType type = BtType::Any;
  std::optional<std::string> default_value;  // literal or "{key}"

  static PortSpec input(std::string n, BtType t, std::optional<std::string> def = std::nullopt) {
    return {std::move(n), PortDir::Input, t, std::move(def)};
  }
  // Output ports default to the blackboard key of the same name ("{name}").
  static PortSpec output(std::string n, BtType t) {
    std::string def = "{" + n + "}";
    return {std::move(n), PortDir::Output, t, std::move(def)};
  }
};
using Ports = std::vector<PortSpec>;

// Called on every status change of every node (for logs, the HTML replay and the run figure).
class Node;
using Observer = std::function<void(const Node& node, Status previous, Status current, double now_s)>;

// Per-tree state the nodes share: the observer. Owned by the BehaviorTree.
struct TreeContext {
  Observer observer;
};

// Everything a node learns from the XML: its type ID, instance name, path in the tree,
// port values (attribute text, defaults filled in), the blackboard of its (sub)tree.
struct NodeConfig {
  std::string id;    // node type ("FollowPath", "Sequence")
  std::string name;  // the `name` attribute, else the ID
  std::string path;  // "Navigate/RestartOnGoalUpdate/.../FollowPath"
  std::string file;  // XML source and line, for messages
  int line = 0;
  std::map<std::string, std::string> ports;
  Ports port_specs;
  std::shared_ptr<Blackboard> blackboard;
  TreeContext* context = nullptr;
};

// Base of every node. Parents call execute_tick(); halt_node() stops a RUNNING node and
// leaves it IDLE. Subclasses implement tick() and, if they keep state across ticks, halt().
class Node {
 public:
  explicit Node(NodeConfig config) : config_(std::move(config)) {}
  virtual ~Node() = default;
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  virtual NodeKind kind() const = 0;

  Status execute_tick(double now_s);
  // Halts this node if RUNNING (recursively), then resets it to IDLE.
  void halt_node();

  Status status() const { return status_; }
  // The last non-IDLE status tick() returned (kept after the parent resets the node).
  Status last_result() const { return last_result_; }
  double last_tick_s() const { return last_tick_s_; }
  const NodeConfig& config() const { return config_; }
  const std::string& name() const { return config_.name; }
  const std::string& id() const { return config_.id; }
  const std::string& path() const { return config_.path; }
  const std::vector<std::unique_ptr<Node>>& children() const { return children_; }
  void add_child(std::unique_ptr<Node> child) { children_.push_back(std::move(child)); }

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
    write_output(port, Value(std::move(value)));
  }

  std::string describe() const;  // "FollowPath 'name' (file:line)"

 protected:
  virtual Status tick(double now_s) = 0;
  // Called by halt_node() only while RUNNING; stop what the node started.
  virtual void halt() {}
  void halt_children();
  void halt_child(std::size_t i) { children_[i]->halt_node(); }
  Node& child(std::size_t i) { return *children_[i]; }
  std::size_t child_count() const { return children_.size(); }
  void set_status(Status s, double now_s);

 private:
  std::optional<Value> input_value(const std::string& port, BtType type) const;
  void write_output(const std::string& port, Value value);

  NodeConfig config_;
  std::vector<std::unique_ptr<Node>> children_;
  Status status_ = Status::IDLE;
  Status last_result_ = Status::IDLE;
  double last_tick_s_ = 0.0;
};

// A synchronous check: SUCCESS when check() is true, FAILURE otherwise, never RUNNING.
class Condition : public Node {
 public:
  using Node::Node;
  NodeKind kind() const override { return NodeKind::Condition; }

 protected:
  virtual bool check(double now_s) = 0;
  Status tick(double now_s) final { return check(now_s) ? Status::SUCCESS : Status::FAILURE; }
};

// A condition given as a function (convenient for bindings that just read the server).
class LambdaCondition final : public Condition {
 public:
  using Fn = std::function<bool(Node& self, double now_s)>;
  LambdaCondition(NodeConfig config, Fn fn) : Condition(std::move(config)), fn_(std::move(fn)) {}

 protected:
  bool check(double now_s) override { return fn_(*this, now_s); }

 private:
  Fn fn_;
};

// A long action spanning ticks (BehaviorTree.CPP's StatefulActionNode): on_start() on the
// first tick, on_running() on later ticks while RUNNING, on_halted() when preempted.
class StatefulAction : public Node {
 public:
  using Node::Node;
  NodeKind kind() const override { return NodeKind::Action; }

 protected:
  virtual Status on_start(double now_s) = 0;
  virtual Status on_running(double now_s) = 0;
  virtual void on_halted() = 0;

  Status tick(double now_s) final;
  void halt() final { on_halted(); }
};

// A stateful action given as functions: `step(self, now_s, first)` is called with first=true
// on the tick that starts the action and false on later ticks while it is RUNNING;
// `halted(self)` when it is preempted (may be empty).
class LambdaAction final : public StatefulAction {
 public:
  using StepFn = std::function<Status(Node& self, double now_s, bool first)>;
  using HaltFn = std::function<void(Node& self)>;
  LambdaAction(NodeConfig config, StepFn step, HaltFn halted)
      : StatefulAction(std::move(config)), step_(std::move(step)), halted_(std::move(halted)) {}

 protected:
  Status on_start(double now_s) override { return step_(*this, now_s, true); }
  Status on_running(double now_s) override { return step_(*this, now_s, false); }
  void on_halted() override {
    if (halted_) halted_(*this);
  }

 private:
  StepFn step_;
  HaltFn halted_;
};

// The literal value of a built-in node's parameter port (defaults already filled in).
// Throws FileError naming the XML line when it is missing or not a literal of `type`.
Value bt_literal_param(const NodeConfig& config, const std::string& port, BtType type);
// The same for an Int port.
int bt_int_param(const NodeConfig& config, const std::string& port);
// Throws FileError naming the node's XML line: a parameter that parsed but makes no sense.
[[noreturn]] void bt_param_error(const NodeConfig& config, const std::string& what);

// Delay's and Sleep's clock: simulated time counted from the first call of elapsed() after
// construction or restart(), read from the node's msec port (an int >= 0).
class SimTimer {
 public:
  SimTimer(const NodeConfig& config, const std::string& msec_port);
  bool elapsed(double now_s);
  void restart() { started_ = false; }

 private:
  double duration_s_ = 0.0;
  bool started_ = false;
  double start_s_ = 0.0;
};

}  // namespace bipednav::bt
