#include "bipednav/bt/xml.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <map>
#include <set>

#include "bipednav/bt/controls.hpp"
#include "bipednav/bt/decorators.hpp"

namespace bipednav::bt {
namespace {

using tinyxml2::XMLElement;

constexpr int kMaxDepth = 200;
// SubTrees used several times expand exponentially: 40 trees of two SubTrees each made 2^40 nodes
// from 4 KB of XML (found by fuzz/fuzz_bt_xml). Real trees have a few hundred nodes; 10000 keeps the rejection well
// under a second.
constexpr std::size_t kMaxNodes = 10000;

const std::set<std::string> kGenericTags = {"Action", "Condition", "Control", "Decorator"};

// The name a node shows in paths: its name attribute, else its type ID.
std::string display_name(const XMLElement& e) {
  if (const char* n = e.Attribute("name")) return n;
  const std::string tag = e.Name();
  if ((kGenericTags.count(tag) != 0 || tag == "SubTree") && e.Attribute("ID") != nullptr) return e.Attribute("ID");
  return tag;
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

// Builds nodes from the parsed document; one instance per load.
class XmlTreeBuilder {
 public:
  XmlTreeBuilder(std::string file, const Factory& factory, TreeContext* context)
      : file_(std::move(file)), factory_(factory), context_(context) {}

  std::string collect_trees(const XMLElement& root);
  std::string root_name(const std::string& id) const { return display_name(*trees_.at(id)->FirstChildElement()); }
  std::unique_ptr<Node> build_tree(const std::string& id, const std::shared_ptr<Blackboard>& bb,
                                   const std::string& path, int depth);

 private:
  [[noreturn]] void fail(const XMLElement& e, const std::string& what) const {
    throw FileError(file_, std::to_string(e.GetLineNum()), what);
  }
  std::unique_ptr<Node> build_node(const XMLElement& e, const std::shared_ptr<Blackboard>& bb, const std::string& path,
                                   int depth);
  std::unique_ptr<Node> build_subtree(const XMLElement& e, const std::shared_ptr<Blackboard>& bb,
                                      const std::string& path, int depth);
  std::map<std::string, std::string> read_ports(const XMLElement& e, const std::string& id, const NodeType& type) const;
  void check_children(const XMLElement& e, const std::string& id, const NodeType& type) const;

  std::string file_;
  const Factory& factory_;
  TreeContext* context_;
  std::map<std::string, const XMLElement*> trees_;
  std::vector<std::string> stack_;  // SubTree IDs being expanded, to detect recursion
  std::size_t nodes_ = 0;           // built so far, against kMaxNodes
};

std::string XmlTreeBuilder::collect_trees(const XMLElement& root) {
  if (std::string(root.Name()) != "root")
    fail(root, "expected the root element <root>, found <" + std::string(root.Name()) + ">");
  if (const char* fmt = root.Attribute("BTCPP_format"); fmt != nullptr && std::string(fmt) != "4")
    fail(root, "expected BTCPP_format=\"4\", found \"" + std::string(fmt) + "\"");
  for (const XMLElement* e = root.FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "TreeNodesModel") continue;
    if (tag != "BehaviorTree")
      fail(*e, "expected <BehaviorTree> or <TreeNodesModel> under <root>, found <" + tag + ">");
    const char* id = e->Attribute("ID");
    if (id == nullptr || std::string(id).empty()) fail(*e, "<BehaviorTree> needs an ID attribute");
    if (!trees_.emplace(id, e).second) fail(*e, "duplicate BehaviorTree ID '" + std::string(id) + "'");
    int n = 0;
    for (const XMLElement* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) ++n;
    if (n != 1)
      fail(*e, "BehaviorTree '" + std::string(id) + "' must have exactly one root node, found " + std::to_string(n));
  }
  if (trees_.empty()) fail(root, "no <BehaviorTree> found");
  if (const char* main = root.Attribute("main_tree_to_execute")) {
    if (trees_.count(main) == 0)
      fail(root, "main_tree_to_execute '" + std::string(main) + "' is not a BehaviorTree ID");
    return main;
  }
  if (trees_.size() != 1) fail(root, "several BehaviorTrees but no main_tree_to_execute attribute");
  return trees_.begin()->first;
}

std::unique_ptr<Node> XmlTreeBuilder::build_tree(const std::string& id, const std::shared_ptr<Blackboard>& bb,
                                                 const std::string& path, int depth) {
  stack_.push_back(id);
  auto node = build_node(*trees_.at(id)->FirstChildElement(), bb, path, depth);
  stack_.pop_back();
  return node;
}

std::map<std::string, std::string> XmlTreeBuilder::read_ports(const XMLElement& e, const std::string& id,
                                                              const NodeType& type) const {
  std::map<std::string, std::string> ports;
  const bool generic = kGenericTags.count(e.Name()) != 0;
  std::vector<std::string> names;
  for (const auto& p : type.ports) names.push_back(p.name);
  for (const auto* a = e.FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string key = a->Name();
    if (key == "name" || (generic && key == "ID")) continue;
    const auto spec =
        std::find_if(type.ports.begin(), type.ports.end(), [&](const PortSpec& p) { return p.name == key; });
    if (spec == type.ports.end())
      fail(e, id + ": unknown attribute '" + key + "'; expected " +
                  (names.empty() ? "none besides name" : "one of: " + join(names, ", ")));
    ports[key] = a->Value();
  }
  for (const auto& p : type.ports) {
    if (ports.count(p.name) == 0) {
      if (!p.default_value)
        fail(e, id + ": missing required port '" + p.name + "' (" + std::string(bt_type_name(p.type)) + ")");
      ports[p.name] = *p.default_value;
    }
    const std::string& v = ports[p.name];
    std::string key;
    const bool ref = bt_is_reference(v, &key);
    if (p.dir != PortDir::Input && !ref)
      fail(e, id + ": output port '" + p.name + "' must be a blackboard key \"{key}\", found \"" + v + "\"");
    if (ref && key.find_first_of("{} ") != std::string::npos)
      fail(e, id + ": port '" + p.name + "' has a malformed key \"" + v + "\"");
    if (!ref && !bt_parse_literal(v, p.type))
      fail(e, id + ": bad value \"" + v + "\" for port '" + p.name + "'; expected a " +
                  std::string(bt_type_name(p.type)) + " or \"{key}\"");
  }
  return ports;
}

void XmlTreeBuilder::check_children(const XMLElement& e, const std::string& id, const NodeType& type) const {
  int n = 0;
  for (const XMLElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) ++n;
  const bool ok = n >= type.min_children && (type.max_children < 0 || n <= type.max_children);
  if (ok) return;
  std::string expected = type.max_children < 0 ? "at least " + std::to_string(type.min_children)
                         : type.min_children == type.max_children
                             ? "exactly " + std::to_string(type.min_children)
                             : std::to_string(type.min_children) + " to " + std::to_string(type.max_children);
  fail(e, id + " (" + std::string(bt_kind_name(type.kind)) + ") expects " + expected + " children, found " +
              std::to_string(n));
}

std::unique_ptr<Node> XmlTreeBuilder::build_node(const XMLElement& e, const std::shared_ptr<Blackboard>& bb,
                                                 const std::string& path, int depth) {
  if (depth > kMaxDepth) fail(e, "tree deeper than " + std::to_string(kMaxDepth) + " levels");
  if (++nodes_ > kMaxNodes)
    fail(e, "tree expands to more than " + std::to_string(kMaxNodes) + " nodes (SubTrees nested and repeated?)");
  const std::string tag = e.Name();
  if (tag == "SubTree") return build_subtree(e, bb, path, depth);
  std::string id = tag;
  if (kGenericTags.count(tag) != 0) {
    const char* attr = e.Attribute("ID");
    if (attr == nullptr) fail(e, "<" + tag + "> needs an ID attribute");
    id = attr;
  }
  const NodeType* type = factory_.find(id);
  if (type == nullptr)
    fail(e, "unknown node type '" + id +
                "'; expected a built-in node or one of the registered leaves: " + join(factory_.ids(), ", "));
  check_children(e, id, *type);
  NodeConfig cfg;
  cfg.id = id;
  cfg.name = e.Attribute("name") != nullptr ? e.Attribute("name") : id;
  cfg.path = path;
  cfg.file = file_;
  cfg.line = e.GetLineNum();
  cfg.ports = read_ports(e, id, *type);
  cfg.port_specs = type->ports;
  cfg.blackboard = bb;
  cfg.context = context_;
  std::unique_ptr<Node> node;
  try {
    node = type->build(cfg);
  } catch (const FileError&) {
    throw;
  } catch (const std::exception& ex) {
    fail(e, "cannot create " + id + ": " + ex.what());
  }
  if (!node) fail(e, "the builder of " + id + " returned no node");
  std::map<std::string, int> seen;
  for (const XMLElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    const std::string name = display_name(*c);
    const int k = seen[name]++;
    node->add_child(build_node(*c, bb, cfg.path + "/" + name + (k > 0 ? "#" + std::to_string(k) : ""), depth + 1));
  }
  if (auto* parallel = dynamic_cast<Parallel*>(node.get())) parallel->validate_children();
  return node;
}

std::unique_ptr<Node> XmlTreeBuilder::build_subtree(const XMLElement& e, const std::shared_ptr<Blackboard>& bb,
                                                    const std::string& path, int depth) {
  const char* id_attr = e.Attribute("ID");
  if (id_attr == nullptr) fail(e, "<SubTree> needs an ID attribute");
  const std::string id = id_attr;
  if (trees_.count(id) == 0) fail(e, "SubTree ID '" + id + "' is not a BehaviorTree in this file");
  if (std::find(stack_.begin(), stack_.end(), id) != stack_.end())
    fail(e, "recursive SubTree '" + id + "' (" + join(stack_, " -> ") + " -> " + id + ")");
  if (e.FirstChildElement() != nullptr) fail(e, "<SubTree> must not have child elements");
  auto child_bb = Blackboard::create(bb);
  NodeConfig cfg;
  cfg.id = "SubTree";
  cfg.name = e.Attribute("name") != nullptr ? e.Attribute("name") : id;
  cfg.path = path;
  cfg.file = file_;
  cfg.line = e.GetLineNum();
  cfg.blackboard = child_bb;
  cfg.context = context_;
  for (const auto* a = e.FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string key = a->Name();
    const std::string value = a->Value();
    if (key == "ID" || key == "name") continue;
    if (key == "_autoremap") {
      const auto on = bt_parse_literal(value, BtType::Bool);
      if (!on) fail(e, "SubTree: _autoremap must be true or false, found \"" + value + "\"");
      child_bb->set_autoremap(std::get<bool>(*on));
      continue;
    }
    if (key.empty() || key.front() == '_') fail(e, "SubTree: unsupported attribute '" + key + "'");
    std::string parent_key;
    if (bt_is_reference(value, &parent_key))
      child_bb->remap(key, parent_key);
    else
      child_bb->set_value(key, Value(value));
    cfg.ports[key] = value;
  }
  auto node = std::make_unique<SubTreeNode>(cfg);
  node->add_child(
      build_tree(id, child_bb, cfg.path + "/" + display_name(*trees_.at(id)->FirstChildElement()), depth + 1));
  return node;
}

}  // namespace

BehaviorTree load_tree_xml(const std::string& path_or_xml, const Factory& factory,
                           std::shared_ptr<Blackboard> blackboard) {
  const auto first = path_or_xml.find_first_not_of(" \t\r\n");
  const bool is_text = first != std::string::npos && path_or_xml[first] == '<';
  const std::string file = is_text ? std::string("<xml string>") : path_or_xml;
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLError err =
      is_text ? doc.Parse(path_or_xml.c_str(), path_or_xml.size()) : doc.LoadFile(path_or_xml.c_str());
  if (err == tinyxml2::XML_ERROR_FILE_NOT_FOUND || err == tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED ||
      err == tinyxml2::XML_ERROR_FILE_READ_ERROR)
    throw FileError(file, "", "cannot read the behavior tree file");
  if (err != tinyxml2::XML_SUCCESS)
    throw FileError(file, std::to_string(doc.ErrorLineNum()),
                    std::string("malformed XML: ") + doc.ErrorName() +
                        (doc.ErrorStr() ? std::string(" (") + doc.ErrorStr() + ")" : ""));
  const XMLElement* root = doc.RootElement();
  if (root == nullptr) throw FileError(file, "", "no root element; expected <root BTCPP_format=\"4\">");
  auto context = std::make_unique<TreeContext>();
  XmlTreeBuilder builder(file, factory, context.get());
  const std::string main_id = builder.collect_trees(*root);
  if (!blackboard) blackboard = Blackboard::create();
  auto node = builder.build_tree(main_id, blackboard, main_id + "/" + builder.root_name(main_id), 0);
  return BehaviorTree(std::move(node), std::move(blackboard), std::move(context), main_id);
}

}  // namespace bipednav::bt
