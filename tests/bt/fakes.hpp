#pragma once

#include <map>
#include <string>
#include <vector>

#include "bipednav/bt/factory.hpp"
#include "bipednav/bt/node.hpp"

// Scriptable leaves for the behavior-tree engine tests: conditions read a value by node
// name, actions run for a scripted number of ticks then return a scripted result, and
// everything is logged ("start A", "run A", "halt A", "check C").
namespace bipednav::bt::test {

struct ActionScript {
  int running_ticks = 0;            // ticks returning RUNNING before the result
  Status result = Status::SUCCESS;  // returned afterwards
};

struct Harness {
  std::map<std::string, bool> conditions;       // by node name; absent = true
  std::map<std::string, ActionScript> actions;  // by node name; absent = immediate SUCCESS
  std::vector<std::string> log;

  int count(const std::string& event) const {
    int n = 0;
    for (const auto& e : log) n += e == event ? 1 : 0;
    return n;
  }
};

class ScriptedAction final : public StatefulAction {
 public:
  ScriptedAction(const NodeConfig& cfg, Harness& h) : StatefulAction(cfg), h_(h) {}

 protected:
  Status on_start(double) override {
    h_.log.push_back("start " + name());
    left_ = script().running_ticks;
    return step();
  }
  Status on_running(double) override {
    h_.log.push_back("run " + name());
    return step();
  }
  void on_halted() override { h_.log.push_back("halt " + name()); }

 private:
  ActionScript script() const {
    const auto it = h_.actions.find(name());
    return it == h_.actions.end() ? ActionScript{} : it->second;
  }
  Status step() { return left_-- > 0 ? Status::RUNNING : script().result; }

  Harness& h_;
  int left_ = 0;
};

// Registers "Cond" (condition) and "Act" (action), both without ports, plus "Writer"
// (writes its literal input `value` as a double to output `out`) and "Reader" (SUCCESS
// when its input `in` equals `expect`).
inline Factory make_test_factory(Harness& h) {
  Factory f;
  f.register_simple_condition("Cond", [&h](Node& self, double) {
    h.log.push_back("check " + self.name());
    const auto it = h.conditions.find(self.name());
    return it == h.conditions.end() || it->second;
  });
  f.register_action("Act", [&h](const NodeConfig& cfg) { return std::make_unique<ScriptedAction>(cfg, h); });
  f.register_simple_condition("Writer",
                              [](Node& self, double) {
                                self.set_output("out", self.input<double>("value"));
                                return true;
                              },
                              {PortSpec::input("value", BtType::Double), PortSpec::output("out", BtType::Double)});
  f.register_simple_condition("Reader",
                              [](Node& self, double) {
                                const auto v = self.get_input<double>("in");
                                return v && *v == self.input<double>("expect");
                              },
                              {PortSpec::input("in", BtType::Double), PortSpec::input("expect", BtType::Double)});
  return f;
}

// Wraps a tree body into a one-tree document.
inline std::string one_tree(const std::string& body) {
  return "<root BTCPP_format=\"4\" main_tree_to_execute=\"Main\">\n<BehaviorTree ID=\"Main\">\n" + body +
         "\n</BehaviorTree>\n</root>\n";
}

}  // namespace bipednav::bt::test
