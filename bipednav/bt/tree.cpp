#include "bipednav/bt/tree.hpp"

#include <cmath>
#include <functional>
#include <sstream>

namespace bipednav::bt {
namespace {

void visit(const BtNode& n, int depth, const std::function<void(const BtNode&, int)>& fn) {
  fn(n, depth);
  for (const auto& c : n.children()) visit(*c, depth + 1, fn);
}

bool is_leaf(const BtNode& n) { return n.children().empty(); }

}  // namespace

BehaviorTree::BehaviorTree(std::unique_ptr<BtNode> root, std::shared_ptr<Blackboard> blackboard,
                           std::unique_ptr<BtTreeContext> context, std::string main_tree_id)
    : context_(std::move(context)),
      root_(std::move(root)),
      blackboard_(std::move(blackboard)),
      main_tree_id_(std::move(main_tree_id)) {
  if (!root_ || !blackboard_ || !context_) throw Error("BehaviorTree: needs a root, a blackboard and a context");
}

BtStatus BehaviorTree::tick(double now_s) {
  if (!std::isfinite(now_s)) throw Error("BehaviorTree::tick: time is not finite");
  if (now_s < last_now_s_)
    throw Error("BehaviorTree::tick: time went backwards (" + std::to_string(now_s) + " s after " +
                std::to_string(last_now_s_) + " s)");
  last_now_s_ = now_s;
  if (root_->status() != BtStatus::RUNNING) root_->halt_node();
  return root_->execute_tick(now_s);
}

void BehaviorTree::halt() { root_->halt_node(); }

std::vector<const BtNode*> BehaviorTree::running_leaves() const {
  std::vector<const BtNode*> out;
  visit(*root_, 0, [&](const BtNode& n, int) {
    if (is_leaf(n) && n.status() == BtStatus::RUNNING) out.push_back(&n);
  });
  return out;
}

std::string BehaviorTree::active_leaf() const {
  const BtNode* best = nullptr;
  visit(*root_, 0, [&](const BtNode& n, int) {
    if (!is_leaf(n) || n.last_result() == BtStatus::IDLE) return;
    if (n.status() == BtStatus::RUNNING) {
      if (best == nullptr || best->status() != BtStatus::RUNNING) best = &n;
    } else if (best == nullptr || (best->status() != BtStatus::RUNNING && n.last_tick_s() >= best->last_tick_s())) {
      best = &n;
    }
  });
  return best == nullptr ? std::string() : best->path();
}

std::vector<BtNodeState> BehaviorTree::snapshot() const {
  std::vector<BtNodeState> out;
  visit(*root_, 0, [&](const BtNode& n, int depth) {
    out.push_back({n.path(), n.id(), n.name(), n.kind(), n.status(), n.last_result(), n.last_tick_s(), depth});
  });
  return out;
}

const BtNode* BehaviorTree::find(const std::string& path) const {
  const BtNode* found = nullptr;
  visit(*root_, 0, [&](const BtNode& n, int) {
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
