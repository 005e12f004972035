#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bipednav/bt/xml.hpp"
#include "bt/fakes.hpp"

namespace bipednav::bt {
namespace {

using test::Harness;
using test::make_test_factory;
using test::one_tree;

// Loads `xml`, expects a FileError, and returns its message.
std::string load_error(const std::string& xml) {
  Harness h;
  Factory f = make_test_factory(h);
  f.register_action("Move", [&h](const NodeConfig& c) { return std::make_unique<test::ScriptedAction>(c, h); },
                    {PortSpec::input("speed_mps", BtType::Double), PortSpec::input("goal", BtType::Pose2, "0;0;0"),
                     PortSpec::output("path", BtType::Path)});
  try {
    load_tree_xml(xml, f);
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError for:\n" << xml;
  return {};
}

void expect_error(const std::string& xml, const std::string& where, const std::string& what) {
  const std::string msg = load_error(xml);
  EXPECT_NE(msg.find(where), std::string::npos) << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << msg;
}

TEST(BtXmlErrors, MalformedXmlNamesTheLine) {
  expect_error("<root BTCPP_format=\"4\">\n<BehaviorTree ID=\"Main\">\n<Sequence>\n</BehaviorTree>\n</root>",
               "<xml string>:3", "malformed XML: XML_ERROR_MISMATCHED_ELEMENT");
  expect_error("<root>\n<BehaviorTree ID=\"M\"><AlwaysSuccess name=\"a/></BehaviorTree></root>",
               "<xml string>:", "malformed XML");
  expect_error("<", "<xml string>", "malformed XML");
}

TEST(BtXmlErrors, StructureOfTheDocument) {
  expect_error("<tree/>", ":1", "expected the root element <root>");
  expect_error("<root BTCPP_format=\"3\"><BehaviorTree ID=\"M\"><AlwaysSuccess/></BehaviorTree></root>", ":1",
               "expected BTCPP_format=\"4\"");
  expect_error("<root BTCPP_format=\"4\"></root>", ":1", "no <BehaviorTree>");
  expect_error("<root main_tree_to_execute=\"X\"><BehaviorTree ID=\"M\"><AlwaysSuccess/></BehaviorTree></root>", ":1",
               "main_tree_to_execute 'X'");
  expect_error(
      "<root>\n<BehaviorTree ID=\"A\"><AlwaysSuccess/></BehaviorTree>\n<BehaviorTree ID=\"B\"><AlwaysSuccess/>"
      "</BehaviorTree></root>",
      ":1", "no main_tree_to_execute");
  expect_error("<root>\n<BehaviorTree><AlwaysSuccess/></BehaviorTree></root>", ":2", "needs an ID");
  expect_error("<root>\n<BehaviorTree ID=\"M\"></BehaviorTree></root>", ":2", "exactly one root node");
  expect_error("<root>\n<include path=\"x.xml\"/></root>", ":2", "expected <BehaviorTree>");
}

TEST(BtXmlErrors, UnknownNodesAttributesAndChildren) {
  expect_error(one_tree("<Sequence>\n<Teleport/>\n</Sequence>"), ":4", "unknown node type 'Teleport'");
  expect_error(one_tree("<Action name=\"x\"/>"), ":3", "<Action> needs an ID");
  expect_error(one_tree("<Sequence speed=\"1\"><AlwaysSuccess/></Sequence>"), ":3", "unknown attribute 'speed'");
  expect_error(one_tree("<Move speed_mps=\"1\" sped=\"2\"/>"), ":3", "expected one of: speed_mps, goal, path");
  expect_error(one_tree("<Inverter/>"), ":3", "expects exactly 1 children, found 0");
  expect_error(one_tree("<Inverter><AlwaysSuccess/><AlwaysSuccess/></Inverter>"), ":3", "found 2");
  expect_error(one_tree("<Sequence/>"), ":3", "at least 1");
  expect_error(one_tree("<RecoveryNode><AlwaysSuccess/></RecoveryNode>"), ":3", "exactly 2");
  expect_error(one_tree("<AlwaysSuccess><AlwaysSuccess/></AlwaysSuccess>"), ":3", "exactly 0");
  expect_error(one_tree("<Sequence _skipIf=\"x\"><AlwaysSuccess/></Sequence>"), ":3", "unknown attribute '_skipIf'");
}

TEST(BtXmlErrors, PortsMissingOrMalformed) {
  expect_error(one_tree("<Move/>"), ":3", "missing required port 'speed_mps'");
  expect_error(one_tree("<Move speed_mps=\"fast\"/>"), ":3", "bad value \"fast\" for port 'speed_mps'");
  expect_error(one_tree("<Move speed_mps=\"1\" goal=\"1;2\"/>"), ":3", "port 'goal'; expected a Pose2");
  expect_error(one_tree("<Move speed_mps=\"1\" path=\"p\"/>"), ":3", "output port 'path' must be a blackboard key");
  expect_error(one_tree("<Move speed_mps=\"{a b}\"/>"), ":3", "malformed key");
  expect_error(one_tree("<RetryUntilSuccessful><AlwaysFailure/></RetryUntilSuccessful>"), ":3",
               "missing required port 'num_attempts'");
  expect_error(one_tree("<RetryUntilSuccessful num_attempts=\"0\"><AlwaysFailure/></RetryUntilSuccessful>"), ":3",
               "num_attempts must be");
  expect_error(one_tree("<RateController hz=\"-2\"><AlwaysFailure/></RateController>"), ":3", "hz must be > 0");
  expect_error(one_tree("<RateController hz=\"{rate}\"><AlwaysFailure/></RateController>"), ":3",
               "is not a literal double");
  expect_error(one_tree("<Delay delay_msec=\"1.5\"><AlwaysFailure/></Delay>"), ":3", "expected a int");
  expect_error(one_tree("<Sleep msec=\"-5\"/>"), ":3", "msec must be >= 0");
  expect_error(one_tree("<Parallel success_count=\"3\"><AlwaysSuccess/><AlwaysSuccess/></Parallel>"), ":3",
               "must be in [1, 2]");
  expect_error(one_tree("<RecoveryNode number_of_retries=\"-1\"><AlwaysSuccess/><AlwaysSuccess/></RecoveryNode>"), ":3",
               "number_of_retries must be >= 0");
}

TEST(BtXmlErrors, SubTreeIdsAndRecursion) {
  expect_error(one_tree("<SubTree ID=\"Nope\"/>"), ":3", "SubTree ID 'Nope' is not a BehaviorTree");
  expect_error(one_tree("<SubTree/>"), ":3", "<SubTree> needs an ID");
  expect_error(
      "<root main_tree_to_execute=\"A\">\n<BehaviorTree ID=\"A\"><SubTree ID=\"B\" "
      "_autoremap=\"maybe\"/></BehaviorTree>\n"
      "<BehaviorTree ID=\"B\"><AlwaysSuccess/></BehaviorTree></root>",
      ":2", "_autoremap must be true or false");
  expect_error(one_tree("<SubTree ID=\"Main\"/>"), ":3", "recursive SubTree 'Main' (Main -> Main)");
  expect_error(
      "<root main_tree_to_execute=\"A\">\n<BehaviorTree ID=\"A\"><SubTree ID=\"B\"/></BehaviorTree>\n"
      "<BehaviorTree ID=\"B\">\n<Sequence><SubTree ID=\"A\"/></Sequence></BehaviorTree></root>",
      ":4", "recursive SubTree 'A' (A -> B -> A)");
}

// Found by fuzz/fuzz_bt_xml: 40 trees each using the next one twice expanded to 2^40 nodes.
TEST(BtXmlErrors, ExponentialSubTreeExpansionIsRejected) {
  std::ostringstream xml;
  xml << "<root BTCPP_format=\"4\" main_tree_to_execute=\"T0\">\n";
  for (int i = 0; i < 39; ++i)
    xml << "<BehaviorTree ID=\"T" << i << "\"><Sequence><SubTree ID=\"T" << i + 1 << "\"/><SubTree ID=\"T" << i + 1
        << "\"/></Sequence></BehaviorTree>\n";
  xml << "<BehaviorTree ID=\"T39\"><AlwaysSuccess/></BehaviorTree>\n</root>\n";
  expect_error(xml.str(), "<xml string>:", "tree expands to more than 10000 nodes");
}

TEST(BtXmlErrors, FilesAreNamedInMessages) {
  const auto dir = std::filesystem::temp_directory_path() / "bipednav_bt_xml_errors";
  std::filesystem::create_directories(dir);
  const auto file = (dir / "bad.xml").string();
  std::ofstream(file) << one_tree("<Sequence>\n\n<Teleport/>\n</Sequence>");
  expect_error(file, file + ":5", "unknown node type 'Teleport'");
  expect_error((dir / "missing.xml").string(), "missing.xml", "cannot read");
  std::filesystem::remove_all(dir);
}

TEST(BtXmlErrors, FactoryRejectsDuplicatesAndReservedNames) {
  Factory f;
  auto build = [](const NodeConfig&) -> std::unique_ptr<Node> { return nullptr; };
  EXPECT_THROW(f.register_action("Sequence", build), Error);
  EXPECT_THROW(f.register_action("SubTree", build), Error);
  EXPECT_THROW(f.register_action("X", build, {PortSpec::input("name", BtType::Any)}), Error);
  f.register_action("X", build);
  EXPECT_THROW(f.register_action("X", build), Error);
  // A builder that returns nothing is reported at load time.
  const std::string msg = [&] {
    try {
      load_tree_xml(one_tree("<X/>"), f);
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(msg.find("returned no node"), std::string::npos) << msg;
}

}  // namespace
}  // namespace bipednav::bt
