#include <gtest/gtest.h>

#include "bipednav/bt/xml.hpp"
#include "bt/fakes.hpp"

namespace bipednav::bt {
namespace {

using test::ActionScript;
using test::Harness;
using test::make_test_factory;
using test::one_tree;

struct EngineTest : ::testing::Test {
  Harness h;
  Factory f = make_test_factory(h);
  BehaviorTree load(const std::string& body) { return load_tree_xml(one_tree(body), f); }
};

TEST_F(EngineTest, SequenceRemembersRunningChild) {
  h.actions["A"] = {2, Status::SUCCESS};
  auto tree = load(R"(<Sequence><Cond name="C"/><Act name="A"/><Act name="B"/></Sequence>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.2), Status::SUCCESS);
  EXPECT_EQ(h.count("check C"), 1);  // not re-evaluated while A runs
  EXPECT_EQ(h.count("start A"), 1);
  EXPECT_EQ(h.count("run A"), 2);
  EXPECT_EQ(h.count("start B"), 1);
  // Completed: the next tick starts over.
  EXPECT_EQ(tree.tick(0.3), Status::RUNNING);
  EXPECT_EQ(h.count("check C"), 2);
}

TEST_F(EngineTest, SequenceFailureRestartsFromFirstChild) {
  h.actions["B"] = {0, Status::FAILURE};
  auto tree = load(R"(<Sequence><Act name="A"/><Act name="B"/><Act name="Z"/></Sequence>)");
  EXPECT_EQ(tree.tick(0.0), Status::FAILURE);
  EXPECT_EQ(h.count("start Z"), 0);
  EXPECT_EQ(tree.tick(0.1), Status::FAILURE);
  EXPECT_EQ(h.count("start A"), 2);
}

TEST_F(EngineTest, FallbackStopsAtFirstSuccessAndRemembersRunning) {
  h.conditions["C"] = false;
  h.actions["A"] = {1, Status::SUCCESS};
  auto tree = load(R"(<Fallback><Cond name="C"/><Act name="A"/><Act name="Z"/></Fallback>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.1), Status::SUCCESS);
  EXPECT_EQ(h.count("check C"), 1);
  EXPECT_EQ(h.count("start Z"), 0);
  h.actions["A"] = {0, Status::FAILURE};
  h.actions["Z"] = {0, Status::FAILURE};
  EXPECT_EQ(tree.tick(0.2), Status::FAILURE);
}

TEST_F(EngineTest, ReactiveSequenceReevaluatesAndHaltsRunningChild) {
  h.actions["A"] = {100, Status::SUCCESS};
  auto tree = load(R"(<ReactiveSequence><Cond name="C"/><Act name="A"/></ReactiveSequence>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);
  EXPECT_EQ(h.count("check C"), 2);
  h.conditions["C"] = false;
  EXPECT_EQ(tree.tick(0.2), Status::FAILURE);
  EXPECT_EQ(h.count("halt A"), 1);
  EXPECT_EQ(tree.find("Main/ReactiveSequence/A")->status(), Status::IDLE);
}

TEST_F(EngineTest, ReactiveSequenceHaltsLaterChildWhenEarlierOneRuns) {
  h.actions["A"] = {0, Status::SUCCESS};
  h.actions["B"] = {100, Status::SUCCESS};
  auto tree = load(R"(<ReactiveSequence><Act name="A"/><Act name="B"/></ReactiveSequence>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);  // B running
  h.actions["A"] = {5, Status::SUCCESS};
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);  // A now runs: B halted
  EXPECT_EQ(h.count("halt B"), 1);
  const auto running = tree.running_leaves();
  ASSERT_EQ(running.size(), 1u);
  EXPECT_EQ(running[0]->name(), "A");
}

TEST_F(EngineTest, ReactiveFallbackHaltsRunningChildWhenConditionSucceeds) {
  h.conditions["Done"] = false;
  h.actions["A"] = {100, Status::SUCCESS};
  auto tree = load(R"(<ReactiveFallback><Cond name="Done"/><Act name="A"/></ReactiveFallback>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);
  h.conditions["Done"] = true;
  EXPECT_EQ(tree.tick(0.2), Status::SUCCESS);
  EXPECT_EQ(h.count("halt A"), 1);
  EXPECT_EQ(h.count("check Done"), 3);
}

TEST_F(EngineTest, ParallelSuccessThresholdHaltsTheOthers) {
  h.actions["Short"] = {2, Status::SUCCESS};
  h.actions["Long"] = {100, Status::SUCCESS};
  auto tree = load(R"(<Parallel success_count="1" failure_count="1"><Act name="Short"/><Act name="Long"/></Parallel>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);
  EXPECT_EQ(tree.running_leaves().size(), 2u);
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.2), Status::SUCCESS);
  EXPECT_EQ(h.count("halt Long"), 1);
  EXPECT_EQ(h.count("halt Short"), 0);
}

TEST_F(EngineTest, ParallelDefaultNeedsAllAndDoesNotReTickFinishedChildren) {
  h.actions["A"] = {0, Status::SUCCESS};
  h.actions["B"] = {2, Status::SUCCESS};
  auto tree = load(R"(<Parallel><Act name="A"/><Act name="B"/></Parallel>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.2), Status::SUCCESS);
  EXPECT_EQ(h.count("start A"), 1);
}

TEST_F(EngineTest, ParallelFailureThreshold) {
  h.actions["F1"] = {1, Status::FAILURE};
  h.actions["F2"] = {0, Status::FAILURE};
  h.actions["Long"] = {100, Status::SUCCESS};
  auto tree = load(
      R"(<Parallel success_count="1" failure_count="2"><Act name="F1"/><Act name="F2"/><Act name="Long"/></Parallel>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);  // one failure so far
  EXPECT_EQ(tree.tick(0.1), Status::FAILURE);  // second failure
  EXPECT_EQ(h.count("halt Long"), 1);
}

TEST_F(EngineTest, ParallelFailsWhenSuccessBecomesImpossible) {
  h.actions["F"] = {0, Status::FAILURE};
  h.actions["Long"] = {100, Status::SUCCESS};
  auto tree = load(R"(<Parallel success_count="-1" failure_count="2"><Act name="F"/><Act name="Long"/></Parallel>)");
  EXPECT_EQ(tree.tick(0.0), Status::FAILURE);
}

TEST_F(EngineTest, RetryUntilSuccessfulCountsAttempts) {
  h.actions["A"] = {0, Status::FAILURE};
  auto tree = load(R"(<RetryUntilSuccessful num_attempts="3"><Act name="A"/></RetryUntilSuccessful>)");
  EXPECT_EQ(tree.tick(0.0), Status::FAILURE);
  EXPECT_EQ(h.count("start A"), 3);
  // Succeeds on the second attempt of a fresh activation; a running attempt spans ticks.
  h.log.clear();
  h.actions["A"] = {1, Status::FAILURE};
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.2), Status::RUNNING);  // attempt 1 failed, attempt 2 started
  h.actions["A"] = {0, Status::SUCCESS};
  EXPECT_EQ(tree.tick(0.3), Status::SUCCESS);
  EXPECT_EQ(h.count("start A"), 2);
}

TEST_F(EngineTest, RateControllerTicksChildAtRateOnSimulatedTime) {
  auto tree = load(
      R"(<KeepRunningUntilFailure><RateController hz="5"><Act name="A"/></RateController></KeepRunningUntilFailure>)");
  for (int i = 0; i < 20; ++i) EXPECT_EQ(tree.tick(0.05 * i), Status::RUNNING);  // 0 .. 0.95 s
  EXPECT_EQ(h.count("start A"), 5);                                              // at 0, 0.2, 0.4, 0.6, 0.8 s
  // Time jumps do not make it catch up.
  EXPECT_EQ(tree.tick(10.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(10.05), Status::RUNNING);
  EXPECT_EQ(h.count("start A"), 6);
}

TEST_F(EngineTest, RateControllerKeepsTickingARunningChildAndReturnsLastResultWhenThrottled) {
  h.actions["A"] = {2, Status::FAILURE};
  auto tree = load(R"(<RateController hz="1"><Act name="A"/></RateController>)");
  EXPECT_EQ(tree.tick(0.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.1), Status::RUNNING);
  EXPECT_EQ(tree.tick(0.2), Status::FAILURE);
  EXPECT_EQ(tree.tick(0.3), Status::FAILURE);  // throttled: last result
  EXPECT_EQ(h.count("start A"), 1);
  EXPECT_EQ(h.count("run A"), 2);
  h.actions["A"] = {0, Status::SUCCESS};
  EXPECT_EQ(tree.tick(1.0), Status::SUCCESS);
  EXPECT_EQ(h.count("start A"), 2);
}

TEST_F(EngineTest, DelayWaitsOnSimulatedTime) {
  auto tree = load(R"(<Delay delay_msec="300"><Act name="A"/></Delay>)");
  EXPECT_EQ(tree.tick(5.0), Status::RUNNING);
  EXPECT_EQ(tree.tick(5.2), Status::RUNNING);
  EXPECT_EQ(h.count("start A"), 0);
  EXPECT_EQ(tree.tick(5.3), Status::SUCCESS);
  EXPECT_EQ(h.count("start A"), 1);
  // A new activation waits again.
  EXPECT_EQ(tree.tick(5.4), Status::RUNNING);
  tree.halt();
  EXPECT_EQ(tree.tick(5.5), Status::RUNNING);
  EXPECT_EQ(tree.tick(5.79), Status::RUNNING);
  EXPECT_EQ(tree.tick(5.8), Status::SUCCESS);
}

// As in the safety gate: a timer ahead of a failure, restarted by a halt from above.
TEST_F(EngineTest, SleepWaitsOnSimulatedTimeThenSucceeds) {
  auto tree = load(R"(<Sequence><Sleep msec="300"/><Act name="A"/><AlwaysFailure/></Sequence>)");
  h.actions["A"] = {0, Status::SUCCESS};
  for (const double t : {5.0, 5.1, 5.29}) EXPECT_EQ(tree.tick(t), Status::RUNNING) << t;
  EXPECT_EQ(h.count("start A"), 0);
  EXPECT_EQ(tree.tick(5.3), Status::FAILURE);
  EXPECT_EQ(h.count("start A"), 1);
  EXPECT_EQ(tree.tick(6.0), Status::RUNNING);  // a new activation sleeps again
  tree.halt();
  for (const double t : {6.1, 6.39}) EXPECT_EQ(tree.tick(t), Status::RUNNING) << t;  // counted from 6.1
  EXPECT_EQ(tree.tick(6.4), Status::FAILURE);
  EXPECT_EQ(h.count("start A"), 2);
}

TEST_F(EngineTest, InverterForceAndKeepRunning) {
  h.conditions["F"] = false;
  EXPECT_EQ(load(R"(<Inverter><Cond name="F"/></Inverter>)").tick(0), Status::SUCCESS);
  EXPECT_EQ(load(R"(<Inverter><Cond name="T"/></Inverter>)").tick(0), Status::FAILURE);
  EXPECT_EQ(load(R"(<ForceSuccess><Cond name="F"/></ForceSuccess>)").tick(0), Status::SUCCESS);
  EXPECT_EQ(load(R"(<ForceFailure><Cond name="T"/></ForceFailure>)").tick(0), Status::FAILURE);
  h.actions["R"] = {1, Status::SUCCESS};
  EXPECT_EQ(load(R"(<Inverter><Act name="R"/></Inverter>)").tick(0), Status::RUNNING);
  auto keep = load(R"(<KeepRunningUntilFailure><Act name="K"/></KeepRunningUntilFailure>)");
  EXPECT_EQ(keep.tick(0), Status::RUNNING);
  EXPECT_EQ(keep.tick(1), Status::RUNNING);
  EXPECT_EQ(h.count("start K"), 2);
  h.actions["K"] = {0, Status::FAILURE};
  EXPECT_EQ(keep.tick(2), Status::FAILURE);
  EXPECT_EQ(load("<AlwaysSuccess/>").tick(0), Status::SUCCESS);
  EXPECT_EQ(load("<AlwaysFailure/>").tick(0), Status::FAILURE);
}

TEST_F(EngineTest, RecoveryNodeRetriesMainAfterEachSuccessfulRecovery) {
  h.actions["Main"] = {0, Status::FAILURE};
  auto tree = load(R"(<RecoveryNode number_of_retries="2"><Act name="Main"/><Act name="Fix"/></RecoveryNode>)");
  EXPECT_EQ(tree.tick(0.0), Status::FAILURE);
  EXPECT_EQ(h.count("start Main"), 3);
  EXPECT_EQ(h.count("start Fix"), 2);
  // A failing recovery ends it at once; a main success ends it with SUCCESS.
  h.log.clear();
  h.actions["Fix"] = {0, Status::FAILURE};
  EXPECT_EQ(tree.tick(0.1), Status::FAILURE);
  EXPECT_EQ(h.count("start Main"), 1);
  h.actions["Main"] = {0, Status::SUCCESS};
  EXPECT_EQ(tree.tick(0.2), Status::SUCCESS);
}

TEST_F(EngineTest, RoundRobinCyclesAcrossActivations) {
  h.actions["B"] = {0, Status::FAILURE};
  auto tree = load(R"(<RoundRobin><Act name="A"/><Act name="B"/><Act name="C"/></RoundRobin>)");
  EXPECT_EQ(tree.tick(0.0), Status::SUCCESS);  // A
  EXPECT_EQ(tree.tick(0.1), Status::SUCCESS);  // B fails, C
  EXPECT_EQ(tree.tick(0.2), Status::SUCCESS);  // A again
  const std::vector<std::string> expected = {"start A", "start B", "start C", "start A"};
  EXPECT_EQ(h.log, expected);
  h.actions["A"] = {0, Status::FAILURE};
  h.actions["C"] = {0, Status::FAILURE};
  EXPECT_EQ(tree.tick(0.3), Status::FAILURE);
}

TEST_F(EngineTest, HaltStopsRunningActionsAndObserverSeesTransitions) {
  h.actions["A"] = {100, Status::SUCCESS};
  auto tree = load(R"(<Sequence name="Root"><Cond name="C"/><Act name="A"/></Sequence>)");
  std::vector<std::string> changes;
  tree.set_observer([&](const Node& n, Status, Status now, double t) {
    changes.push_back(n.name() + ":" + std::string(bt_status_name(now)) + "@" + std::to_string(static_cast<int>(t)));
  });
  EXPECT_EQ(tree.tick(1.0), Status::RUNNING);
  EXPECT_EQ(tree.active_leaf(), "Main/Root/A");
  tree.halt();
  EXPECT_EQ(h.count("halt A"), 1);
  EXPECT_EQ(tree.status(), Status::IDLE);
  EXPECT_TRUE(tree.running_leaves().empty());
  const std::vector<std::string> expected = {"C:SUCCESS@1", "A:RUNNING@1", "Root:RUNNING@1",
                                             "C:IDLE@1",    "A:IDLE@1",    "Root:IDLE@1"};
  EXPECT_EQ(changes, expected);
  const auto snap = tree.snapshot();
  ASSERT_EQ(snap.size(), 3u);
  EXPECT_EQ(snap[2].path, "Main/Root/A");
  EXPECT_EQ(snap[2].last_result, Status::RUNNING);
  EXPECT_EQ(snap[1].depth, 1);
}

TEST_F(EngineTest, TimeMustNotGoBackwards) {
  auto tree = load("<AlwaysSuccess/>");
  tree.tick(2.0);
  EXPECT_THROW(tree.tick(1.0), Error);
}

}  // namespace
}  // namespace bipednav::bt
