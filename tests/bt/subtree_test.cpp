#include <gtest/gtest.h>

#include "bipednav/bt/xml.hpp"
#include "bt/fakes.hpp"

namespace bipednav::bt {
namespace {

using test::Harness;
using test::make_test_factory;

TEST(BtBlackboard, TypedValuesAndConversions) {
  auto bb = Blackboard::create();
  bb->set("d", 1.5);
  bb->set("i", 3);
  bb->set("s", "2.25");
  bb->set("p", Pose2{1, 2, 0.5});
  EXPECT_EQ(bb->get<double>("d"), 1.5);
  EXPECT_EQ(bb->get<double>("i"), 3.0);   // int widens
  EXPECT_EQ(bb->get<double>("s"), 2.25);  // strings parse
  EXPECT_EQ(bb->get<Pose2>("p")->theta, 0.5);
  EXPECT_FALSE(bb->get<double>("missing").has_value());
  EXPECT_THROW(bb->get<Pose2>("d"), Error);
  EXPECT_THROW(bb->set("d", std::string("x")), Error);  // entries keep their type
  EXPECT_EQ(std::get<Pose2>(*bt_parse_literal("1;-2;0.25", BtType::Pose2)).y, -2.0);
  EXPECT_EQ(std::get<Pose2>(*bt_parse_literal("1, 2, 3", BtType::Pose2)).theta, 3.0);
  EXPECT_FALSE(bt_parse_literal("1;2", BtType::Pose2).has_value());
  EXPECT_FALSE(bt_parse_literal("0.5x", BtType::Double).has_value());
  EXPECT_FALSE(bt_parse_literal("nan", BtType::Double).has_value());
  EXPECT_FALSE(bt_parse_literal("2.0", BtType::Int).has_value());
  EXPECT_EQ(std::get<bool>(*bt_parse_literal("TRUE", BtType::Bool)), true);
}

TEST(BtBlackboard, RemappingAndAutoremap) {
  auto parent = Blackboard::create();
  parent->set("goal", Pose2{4, 5, 0});
  auto child = Blackboard::create(parent);
  child->remap("target", "goal");
  EXPECT_EQ(child->get<Pose2>("target")->x, 4.0);
  EXPECT_FALSE(child->has("goal"));  // no autoremap: isolated
  child->set_autoremap(true);
  EXPECT_TRUE(child->has("goal"));
  child->set("new_key", 1.0);  // autoremap writes through to the parent
  EXPECT_EQ(parent->get<double>("new_key"), 1.0);
  child->set("_private", 2.0);
  EXPECT_FALSE(parent->has("_private"));
}

constexpr const char* kSubtreeXml = R"(<root BTCPP_format="4" main_tree_to_execute="Main">
  <BehaviorTree ID="Main">
    <Sequence>
      <SubTree ID="Produce" out="{result}" value="2.5"/>
      <Reader in="{result}" expect="2.5"/>
      <SubTree ID="Consume" _autoremap="true"/>
      <SubTree ID="Isolated"/>
    </Sequence>
  </BehaviorTree>
  <BehaviorTree ID="Produce">
    <Writer value="{value}" out="{out}"/>
  </BehaviorTree>
  <BehaviorTree ID="Consume">
    <Sequence>
      <Reader in="{result}" expect="2.5"/>
      <Writer value="7" out="{shared}"/>
    </Sequence>
  </BehaviorTree>
  <BehaviorTree ID="Isolated">
    <Inverter><Reader in="{result}" expect="2.5"/></Inverter>
  </BehaviorTree>
</root>)";

TEST(BtSubTree, ExplicitRemappingAutoremapAndIsolation) {
  Harness h;
  const Factory f = make_test_factory(h);
  auto tree = load_tree_xml(kSubtreeXml, f);
  EXPECT_EQ(tree.tick(0.0), Status::SUCCESS);
  EXPECT_EQ(tree.blackboard()->get<double>("result"), 2.5);  // written through the remapped port
  EXPECT_EQ(tree.blackboard()->get<double>("shared"), 7.0);  // autoremap writes to the parent
  EXPECT_FALSE(tree.blackboard()->has("out"));               // the subtree's own key stays inside
  EXPECT_FALSE(tree.blackboard()->has("value"));
  ASSERT_NE(tree.find("Main/Sequence/Produce/Writer"), nullptr);
  EXPECT_EQ(tree.find("Main/Sequence/Produce")->kind(), NodeKind::SubTree);
  EXPECT_NE(tree.find("Main/Sequence/Consume/Sequence/Writer"), nullptr);
}

TEST(BtSubTree, SameSubtreeTwiceGetsSeparateInstancesAndPaths) {
  Harness h;
  const Factory f = make_test_factory(h);
  auto tree = load_tree_xml(R"(<root BTCPP_format="4" main_tree_to_execute="Main">
    <BehaviorTree ID="Main"><Sequence>
      <SubTree ID="W" out="{a}" v="1"/><SubTree ID="W" out="{b}" v="2"/>
    </Sequence></BehaviorTree>
    <BehaviorTree ID="W"><Writer value="{v}" out="{out}"/></BehaviorTree></root>)",
                            f);
  EXPECT_EQ(tree.tick(0.0), Status::SUCCESS);
  EXPECT_EQ(tree.blackboard()->get<double>("a"), 1.0);
  EXPECT_EQ(tree.blackboard()->get<double>("b"), 2.0);
  EXPECT_NE(tree.find("Main/Sequence/W#1/Writer"), nullptr);
}

TEST(BtSubTree, GenericTagsAndSingleTreeWithoutMainAttribute) {
  Harness h;
  const Factory f = make_test_factory(h);
  auto tree = load_tree_xml(R"(<root BTCPP_format="4"><BehaviorTree ID="Only">
      <Control ID="Sequence"><Condition ID="Cond" name="C"/><Action ID="Act" name="A"/></Control>
    </BehaviorTree></root>)",
                            f);
  EXPECT_EQ(tree.main_tree_id(), "Only");
  EXPECT_EQ(tree.tick(0.0), Status::SUCCESS);
  EXPECT_EQ(h.count("check C"), 1);
  EXPECT_EQ(h.count("start A"), 1);
}

TEST(BtSubTree, InitialBlackboardIsTheRoot) {
  Harness h;
  const Factory f = make_test_factory(h);
  auto bb = Blackboard::create();
  bb->set("x", 4.0);
  auto tree = load_tree_xml(test::one_tree(R"(<Reader in="{x}" expect="4"/>)"), f, bb);
  EXPECT_EQ(tree.tick(0.0), Status::SUCCESS);
  bb->set("x", 5.0);
  EXPECT_EQ(tree.tick(0.1), Status::FAILURE);
}

TEST(BtSubTree, SetBlackboardAndGoalUpdated) {
  Harness h;
  const Factory f = make_test_factory(h);
  auto bb = Blackboard::create();
  bb->set("goal", Pose2{1, 0, 0});
  auto tree = load_tree_xml(test::one_tree(R"(<Sequence>
      <SetBlackboard value="{goal}" output_key="active_goal"/>
      <SetBlackboard value="hello" output_key="{greeting}"/>
      <Inverter><GoalUpdated/></Inverter>
    </Sequence>)"),
                            f, bb);
  EXPECT_EQ(tree.tick(0.0), Status::SUCCESS);
  EXPECT_EQ(bb->get<Pose2>("active_goal")->x, 1.0);
  EXPECT_EQ(bb->get<std::string>("greeting"), "hello");
  auto check = load_tree_xml(test::one_tree("<GoalUpdated/>"), f, bb);
  EXPECT_EQ(check.tick(0.0), Status::FAILURE);
  bb->set("goal", Pose2{2, 0, 0});
  EXPECT_EQ(check.tick(0.1), Status::SUCCESS);
}

}  // namespace
}  // namespace bipednav::bt
