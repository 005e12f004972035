// libFuzzer target: behavior-tree XML (bt/xml + bt/factory) with the built-in nodes
// and every navigation leaf of navigate.xml bound to scripted stand-ins; a tree that loads is
// ticked a few times (ports are read at tick time). Input not starting with '<' (after blanks)
// goes through a file, as load_tree_xml treats it as a path.
#include <memory>
#include <string>

#include "bipednav/bt/factory.hpp"
#include "bipednav/bt/xml.hpp"
#include "bipednav/navigation/bt_navigation_leaves.hpp"
#include "fuzz_common.hpp"

namespace {

using namespace bipednav::bt;
using namespace bipednav::navigation;

Factory make_factory() {
  Factory f;
  for (const BtLeafSpec& s : navigation_leaf_specs()) {
    const std::size_t salt = s.id.size();
    if (s.kind == NodeKind::Condition) {
      f.register_simple_condition(
          s.id, [salt](Node&, double now_s) { return (static_cast<std::size_t>(now_s * 10.0) + salt) % 3 != 0; },
          s.ports);
    } else {
      f.register_simple_action(
          s.id,
          [salt](Node&, double now_s, bool first) {
            if (first) return Status::RUNNING;
            return (static_cast<std::size_t>(now_s * 10.0) + salt) % 2 == 0 ? Status::SUCCESS : Status::FAILURE;
          },
          {}, s.ports);
    }
  }
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  static const Factory factory = make_factory();
  std::string xml(fuzz::as_text(data, size));
  const auto first = xml.find_first_not_of(" \t\r\n");
  std::string name = "<xml string>";
  if (first == std::string::npos || xml[first] != '<') {
    name = fuzz::write_file(fuzz::scratch_dir("bt_xml"), "fuzz_tree.xml", xml).string();
    xml = name;
  }
  std::unique_ptr<BehaviorTree> tree;
  fuzz::run_loader([&] { tree = std::make_unique<BehaviorTree>(load_tree_xml(xml, factory)); }, {name});
  if (!tree) return 0;
  try {
    for (int i = 0; i < 8; ++i) tree->tick(0.1 * i);
  } catch (const Error&) {
    // A port whose value only fails at tick time (a blackboard entry of the wrong type) is
    // reported as an Error naming the node; that is the documented behaviour.
  }
  return 0;
}
