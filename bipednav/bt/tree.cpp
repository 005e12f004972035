#include "bipednav/bt/tree.hpp"

#include <cmath>
#include <functional>
#include <sstream>

namespace bipednav::bt {
namespace {

void visit(const Node& n, int depth, const std::function<void(const Node&, int)>& fn) {
  fn(n, depth);
  for (const auto& c : n.children()) visit(*c, depth + 1, fn);
}

bool is_leaf(const Node& n) { return n.children().empty(); }

}  // namespace

BehaviorTree::BehaviorTree(std::unique_ptr<Node> root, std::shared_ptr<Blackboard> blackboard,
                           std::unique_ptr<TreeContext> context, std::string main_tree_id)
    : context_(std::move(context)),
      root_(std::move(root)),
      blackboard_(std::move(blackboard)),
      main_tree_id_(std::move(main_tree_id)) {
  if (!root_ || !blackboard_ || !context_) throw Error("BehaviorTree: needs a root, a blackboard and a context");
}

Status BehaviorTree::tick(double now_s) {
  if (!std::isfinite(now_s)) throw Error("BehaviorTree::tick: time is not finite");
  if (now_s < last_now_s_)
    throw Error("BehaviorTree::tick: time went backwards (" + std::to_string(now_s) + " s after " +
                std::to_string(last_now_s_) + " s)");
  last_now_s_ = now_s;
  if (root_->status() != Status::RUNNING) root_->halt_node();
  return root_->execute_tick(now_s);
}

void BehaviorTree::halt() { root_->halt_node(); }

std::vector<const Node*> BehaviorTree::running_leaves() const {
  std::vector<const Node*> out;
  visit(*root_, 0, [&](const Node& n, int) {
    if (is_leaf(n) && n.status() == Status::RUNNING) out.push_back(&n);
  });
  return out;
}

std::string BehaviorTree::active_leaf() const {
  const Node* best = nullptr;
  visit(*root_, 0, [&](const Node& n, int) {
    if (!is_leaf(n) || n.last_result() == Status::IDLE) return;
    if (n.status() == Status::RUNNING) {
      if (best == nullptr || best->status() != Status::RUNNING) best = &n;
    } else if (best == nullptr || (best->status() != Status::RUNNING && n.last_tick_s() >= best->last_tick_s())) {
      best = &n;
    }
  });
  return best == nullptr ? std::string() : best->path();
}

std::vector<NodeState> BehaviorTree::snapshot() const {
  std::vector<NodeState> out;
  visit(*root_, 0, [&](const Node& n, int depth) {
    out.push_back({n.path(), n.id(), n.name(), n.kind(), n.status(), n.last_result(), n.last_tick_s(), depth});
  });
  return out;
}

const Node* BehaviorTree::find(const std::string& path) const {
  const Node* found = nullptr;
  visit(*root_, 0, [&](const Node& n, int) {
    if (found == nullptr && n.path() == path) found = &n;
  });
  return found;
}

std::string BehaviorTree::to_string() const {
  std::ostringstream os;
  for (const auto& s : snapshot()) {
    os << std::string(2 * static_cast<std::size_t>(s.depth), ' ') << s.name;
    if (s.name != s.id) os << " (" << s.id << ")";
    os << " [" << bt_status_name(s.status) << ", last " << bt_status_name(s.last_result) << "]\n";
  }
  return os.str();
}

}  // namespace bipednav::bt
