#pragma once

#include <memory>
#include <string>

#include "bipednav/bt/factory.hpp"
#include "bipednav/bt/tree.hpp"

namespace bipednav::bt {

// Builds the tree from BehaviorTree.CPP v4-style XML:
//   <root BTCPP_format="4" main_tree_to_execute="Main"> <BehaviorTree ID="Main"> ... </root>
// Nodes are written as <Sequence>, <FollowPath path="{path}"/> or <Action ID="FollowPath"/>
// (also Condition / Control / Decorator), subtrees as <SubTree ID="X" _autoremap="true"
// port="{parent_key}" other="literal"/>. `path_or_xml` is a file path, or the XML text itself
// when it starts with '<'. The tree's root blackboard is `blackboard` (a new one if null).
// Throws FileError naming the file, the line and what was expected for malformed XML, an
// unknown node type or attribute, a missing or malformed port, a wrong number of children,
// an unknown SubTree ID or a recursive SubTree.
BehaviorTree load_tree_xml(const std::string& path_or_xml, const Factory& factory,
                           std::shared_ptr<Blackboard> blackboard = nullptr);

}  // namespace bipednav::bt
