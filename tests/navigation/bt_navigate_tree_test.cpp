#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <fstream>
#include <map>
#include <sstream>

#include "bipednav/bt/xml.hpp"
#include "bipednav/common/outcome.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/navigation/bt_navigation_leaves.hpp"
#include "bt/fakes.hpp"
#include "test_data.hpp"

// The default tree (config/behavior_trees/navigate.xml) with its leaves bound to a scripted
// fake navigation server.
namespace bipednav::navigation {
namespace {

struct FakeNav {
  // Script.
  bool sensors_ok = true, localization_ok = true, start_ok = true, goal_ok = true;
  bool can_rotate = true, path_valid = true, goal_reached = false;
  bool plan_ok = true;
  std::deque<bool> plan_results;         // the outcomes of the first plans, then plan_ok
  int planning_recoveries_left = 1000;   // PlanningRecoveryAllowed admits this many
  int follow_ticks = 20;                 // FollowPath succeeds on its n-th tick
  std::deque<int> follow_failure_codes;  // each run fails on its 3rd tick with the next code
  // Record.
  std::vector<std::string> log;
  std::vector<Pose2> planned_goals;
  std::map<std::string, double> started_s;
  int follow_tick = 0;

  int count(const std::string& e) const { return static_cast<int>(std::count(log.begin(), log.end(), e)); }
  std::vector<std::string> recoveries() const {
    std::vector<std::string> out;
    for (const auto& e : log)
      if (e == "ClearCostmaps" || e == "BackUp" || e == "RotateInPlace" || e == "Wait" || e == "RelaxConstraints")
        out.push_back(e);
    return out;
  }
};

// An action that lasts `duration(self)` seconds of tree time.
bt::LambdaAction::StepFn timed(FakeNav& n, std::string label, std::function<double(bt::Node&)> duration) {
  return [&n, label, duration](bt::Node& self, double now_s, bool first) {
    if (first) {
      n.log.push_back(label);
      n.started_s[self.path()] = now_s;
    }
    return now_s - n.started_s[self.path()] + 1e-9 >= duration(self) ? bt::Status::SUCCESS : bt::Status::RUNNING;
  };
}

void bind_conditions(bt::Factory& f, FakeNav& n) {
  auto flag = [&f](const std::string& id, const bool* value) {
    f.register_simple_condition(
        id, [value](bt::Node&, double) { return *value; }, bt_leaf_ports(id));
  };
  flag("SensorsAlive", &n.sensors_ok);
  flag("IsLocalizationHealthy", &n.localization_ok);
  flag("IsStartValid", &n.start_ok);
  flag("CanRotateInPlace", &n.can_rotate);
  flag("IsPathValid", &n.path_valid);
  flag("GoalReached", &n.goal_reached);
  f.register_simple_condition(
      "PlanningRecoveryAllowed",
      [&n](bt::Node&, double) {
        if (n.planning_recoveries_left <= 0) return false;
        --n.planning_recoveries_left;
        return true;
      },
      bt_leaf_ports("PlanningRecoveryAllowed"));
  f.register_simple_condition(
      "IsGoalValid",
      [&n](bt::Node& self, double) {
        if (!n.goal_ok) self.set_output("error_code", static_cast<int>(code(Outcome::BLOCKED_GOAL)));
        return n.goal_ok;
      },
      bt_leaf_ports("IsGoalValid"));
}

void bind_actions(bt::Factory& f, FakeNav& n) {
  f.register_simple_action(
      "ComputePathToPose",
      [&n](bt::Node& self, double, bool) {
        const Pose2 goal = self.input<Pose2>("goal");
        n.planned_goals.push_back(goal);
        n.log.push_back("plan");
        const bool ok = n.plan_results.empty() ? n.plan_ok : n.plan_results.front();
        if (!n.plan_results.empty()) n.plan_results.pop_front();
        if (!ok) {
          self.set_output("error_code", static_cast<int>(code(Outcome::NO_PATH_FOUND)));
          return bt::Status::FAILURE;
        }
        Path p;
        p.poses = {Pose2{}, goal};
        self.set_output("path", p);
        return bt::Status::SUCCESS;
      },
      {}, bt_leaf_ports("ComputePathToPose"));
  f.register_simple_action(
      "FollowPath",
      [&n](bt::Node& self, double, bool first) {
        if (first) {
          n.log.push_back("follow");
          n.follow_tick = 0;
        }
        if (self.input<Path>("path").empty()) return bt::Status::FAILURE;
        ++n.follow_tick;
        if (!n.follow_failure_codes.empty() && n.follow_tick == 3) {
          self.set_output("error_code", n.follow_failure_codes.front());
          n.follow_failure_codes.pop_front();
          return bt::Status::FAILURE;
        }
        return n.follow_tick >= n.follow_ticks ? bt::Status::SUCCESS : bt::Status::RUNNING;
      },
      [&n](bt::Node&) { n.log.push_back("halt FollowPath"); }, bt_leaf_ports("FollowPath"));
  auto instant = [&f, &n](const std::string& id) {
    f.register_simple_action(id, timed(n, id, [](bt::Node&) { return 0.0; }), {}, bt_leaf_ports(id));
  };
  instant("ClearCostmaps");
  instant("RelaxConstraints");
  instant("Stop");
  f.register_simple_action(
      "BackUp",
      timed(n, "BackUp", [](bt::Node& s) { return s.input<double>("distance_m") / s.input<double>("speed_mps"); }),
      [&n](bt::Node&) { n.log.push_back("halt BackUp"); }, bt_leaf_ports("BackUp"));
  f.register_simple_action(
      "RotateInPlace", timed(n, "RotateInPlace", [](bt::Node& s) { return std::abs(s.input<double>("angle_rad")); }),
      {}, bt_leaf_ports("RotateInPlace"));
  f.register_simple_action(
      "Wait", timed(n, "Wait", [](bt::Node& s) { return s.input<double>("duration_s"); }),
      [&n](bt::Node&) { n.log.push_back("halt Wait"); }, bt_leaf_ports("Wait"));
}

struct NavigateTreeTest : ::testing::Test {
  FakeNav nav;
  bt::Factory factory;
  std::shared_ptr<bt::Blackboard> bb = bt::Blackboard::create();
  double t = 0.0;
  int step = 0;

  void SetUp() override {
    bind_conditions(factory, nav);
    bind_actions(factory, nav);
    bb->set("goal", Pose2{3.0, 1.0, 0.0});
  }
  bt::BehaviorTree load() {
    return bt::load_tree_xml((bipednav::test::source_dir() / "config/behavior_trees/navigate.xml").string(), factory,
                             bb);
  }
  // Ticks at 10 Hz until the tree completes or `until_s`; `each` runs before every tick.
  bt::Status run(bt::BehaviorTree& tree, double until_s, const std::function<void(double)>& each = {}) {
    bt::Status s = bt::Status::RUNNING;
    while (s == bt::Status::RUNNING && t <= until_s + 1e-9) {
      if (each) each(t);
      s = tree.tick(t);
      t = ++step * 0.1;
    }
    return s;
  }
  int error_code() const { return bb->get<int>("error_code").value_or(-1); }
};

TEST_F(NavigateTreeTest, AllLeavesAreDeclaredAndBound) {
  EXPECT_TRUE(unbound_navigation_leaves(factory).empty());
  auto tree = load();
  EXPECT_EQ(tree.main_tree_id(), "Navigate");
  EXPECT_NE(tree.find("Navigate/StopOnExit/NavigateThenStop/RestartOnNewGoal/StartNavigation/NavigateUntilPreempted/"
                      "Navigation/NavigationSequence/Planning/PlanWithRecoveries/ComputePathToPose"),
            nullptr);
}

TEST_F(NavigateTreeTest, NormalRunReplansAlongsideControlAndStops) {
  auto tree = load();
  std::vector<std::string> running;
  const bt::Status s = run(tree, 30.0, [&](double now) {
    if (std::abs(now - 1.0) < 1e-6)
      for (const bt::Node* n : tree.running_leaves()) running.push_back(n->name());
  });
  EXPECT_EQ(s, bt::Status::SUCCESS);
  EXPECT_NEAR(t, 2.0, 1e-9);  // FollowPath's 20th tick at 1.9 s
  EXPECT_EQ(nav.count("follow"), 1);
  EXPECT_EQ(nav.count("plan"), 1 + 10);  // initial plan + replans at 0, 0.2, ..., 1.8 s
  EXPECT_TRUE(nav.recoveries().empty());
  EXPECT_EQ(nav.log.back(), "Stop");
  EXPECT_EQ(nav.count("Stop"), 1);
  EXPECT_EQ(running, std::vector<std::string>{"FollowPath"});
  EXPECT_EQ(bb->get<Path>("path")->poses.back().x, 3.0);
}

TEST_F(NavigateTreeTest, PlanningFailureCyclesRecoveriesThenFailsWithNoPath) {
  nav.plan_ok = false;
  nav.can_rotate = false;
  auto tree = load();
  EXPECT_EQ(run(tree, 60.0), bt::Status::FAILURE);
  EXPECT_EQ(nav.count("plan"), 5);  // 1 + number_of_retries
  const std::vector<std::string> expected = {"ClearCostmaps", "RelaxConstraints", "BackUp", "Wait"};
  EXPECT_EQ(nav.recoveries(), expected);  // no RotateInPlace: the robot may not turn in place
  EXPECT_EQ(error_code(), code(Outcome::NO_PATH_FOUND));
  EXPECT_EQ(nav.log.back(), "Stop");
  EXPECT_EQ(nav.count("follow"), 0);
}

TEST_F(NavigateTreeTest, PlanningRecoveriesRotateWhereAllowed) {
  nav.plan_ok = false;
  auto tree = load();
  EXPECT_EQ(run(tree, 60.0), bt::Status::FAILURE);
  const std::vector<std::string> expected = {"ClearCostmaps", "RelaxConstraints", "RotateInPlace", "BackUp"};
  EXPECT_EQ(nav.recoveries(), expected);
}

TEST_F(NavigateTreeTest, PlanningRecoveriesStopWhenTheGoalsBudgetIsSpent) {
  nav.plan_ok = false;
  nav.planning_recoveries_left = 2;
  auto tree = load();
  EXPECT_EQ(run(tree, 60.0), bt::Status::FAILURE);
  EXPECT_EQ(nav.count("plan"), 3);
  const std::vector<std::string> expected = {"ClearCostmaps", "RelaxConstraints"};
  EXPECT_EQ(nav.recoveries(), expected);
  EXPECT_EQ(error_code(), code(Outcome::NO_PATH_FOUND));
  EXPECT_EQ(nav.log.back(), "Stop");
}

TEST_F(NavigateTreeTest, PlanningRecoveryBudgetSpansTheNavigation) {
  // The first plan fails and a recovery lets the second succeed; the path cannot be followed
  // (the control recoveries run out) and replanning fails from then on: the two planning
  // recoveries left run, then the navigation ends with NO_PATH_FOUND.
  nav.planning_recoveries_left = 3;
  nav.follow_failure_codes = std::deque<int>(20, code(Outcome::OSCILLATION));
  auto tree = load();
  nav.plan_results = {false, true};
  nav.plan_ok = false;
  EXPECT_EQ(run(tree, 200.0), bt::Status::FAILURE);
  // Planning (1), the four control recoveries, then Replanning's own round robin (2).
  const std::vector<std::string> expected = {"ClearCostmaps", "ClearCostmaps",   "Wait", "BackUp", "RotateInPlace",
                                             "ClearCostmaps", "RelaxConstraints"};
  EXPECT_EQ(nav.recoveries(), expected);
  EXPECT_EQ(nav.planning_recoveries_left, 0);
  EXPECT_EQ(nav.count("follow"), 5);
  EXPECT_EQ(error_code(), code(Outcome::NO_PATH_FOUND));
}

TEST_F(NavigateTreeTest, FailedReplansOnAnInvalidPathSpendThePlanningBudget) {
  // The first plan succeeds; then every replan fails and the path is no longer valid: each such
  // failure spends a planning recovery (two here) before the control recoveries run, and once the
  // budget is spent the Planning sub-tree's failure ends the navigation without recoveries of its own.
  nav.planning_recoveries_left = 2;
  nav.plan_results = {true};
  nav.plan_ok = false;
  nav.path_valid = false;
  auto tree = load();
  EXPECT_EQ(run(tree, 200.0), bt::Status::FAILURE);
  const std::vector<std::string> expected = {"ClearCostmaps", "Wait", "BackUp", "RotateInPlace"};
  EXPECT_EQ(nav.recoveries(), expected);
  EXPECT_EQ(nav.planning_recoveries_left, 0);
  EXPECT_EQ(error_code(), code(Outcome::NO_PATH_FOUND));
  EXPECT_EQ(nav.log.back(), "Stop");
}

TEST_F(NavigateTreeTest, ControlFailureRecoversAndSucceeds) {
  nav.follow_failure_codes = {code(Outcome::BLOCKED_PATH)};
  auto tree = load();
  EXPECT_EQ(run(tree, 30.0), bt::Status::SUCCESS);
  EXPECT_EQ(nav.count("follow"), 2);
  EXPECT_EQ(nav.recoveries(), std::vector<std::string>{"ClearCostmaps"});
  EXPECT_EQ(error_code(), code(Outcome::BLOCKED_PATH));  // the last controller failure, for the log
  EXPECT_EQ(nav.log.back(), "Stop");
}

TEST_F(NavigateTreeTest, ExhaustedControlRecoveriesRerunPlanning) {
  nav.follow_failure_codes = std::deque<int>(5, code(Outcome::ROBOT_STUCK));
  auto tree = load();
  EXPECT_EQ(run(tree, 120.0), bt::Status::SUCCESS);
  EXPECT_EQ(nav.count("follow"), 6);
  const std::vector<std::string> expected = {"ClearCostmaps", "Wait", "BackUp", "RotateInPlace"};
  EXPECT_EQ(nav.recoveries(), expected);
  // The Planning sub-tree ran again between the 5th and the 6th control attempt.
  const auto fifth = std::find(nav.log.rbegin(), nav.log.rend(), "follow");
  EXPECT_EQ(*std::next(fifth), "plan");
}

TEST_F(NavigateTreeTest, NewGoalPreemptsAndIsReached) {
  nav.follow_ticks = 30;
  auto tree = load();
  const Pose2 new_goal{5.0, 5.0, 1.0};
  const bt::Status s = run(tree, 30.0, [&](double now) {
    if (std::abs(now - 1.0) < 1e-6) bb->set("goal", new_goal);
  });
  EXPECT_EQ(s, bt::Status::SUCCESS);
  EXPECT_EQ(nav.count("halt FollowPath"), 1);
  EXPECT_EQ(nav.count("follow"), 2);
  EXPECT_EQ(bb->get<Pose2>("active_goal")->x, 5.0);
  EXPECT_EQ(nav.planned_goals.back().y, 5.0);
  EXPECT_EQ(bb->get<Path>("path")->poses.back().theta, 1.0);
  EXPECT_NEAR(t, 1.0 + 3.0, 1e-9);  // the second run needs its own 30 ticks
}

TEST_F(NavigateTreeTest, GoalReachedEndsControlEarly) {
  nav.follow_ticks = 1000;
  auto tree = load();
  EXPECT_EQ(run(tree, 30.0, [&](double now) { nav.goal_reached = now > 1.45; }), bt::Status::SUCCESS);
  EXPECT_EQ(nav.count("halt FollowPath"), 1);
  EXPECT_EQ(nav.log.back(), "Stop");
}

TEST_F(NavigateTreeTest, BlockedGoalFailsAfterValidationRecoveries) {
  nav.goal_ok = false;
  auto tree = load();
  EXPECT_EQ(run(tree, 30.0), bt::Status::FAILURE);
  EXPECT_EQ(error_code(), code(Outcome::BLOCKED_GOAL));
  EXPECT_EQ(nav.recoveries(), (std::vector<std::string>{"ClearCostmaps", "BackUp"}));
  EXPECT_EQ(nav.count("plan"), 0);
  EXPECT_EQ(nav.log.back(), "Stop");
}

TEST_F(NavigateTreeTest, SilentSensorsStopTheRobotAndNavigationResumes) {
  auto tree = load();
  const bt::Status s = run(tree, 30.0, [&](double now) { nav.sensors_ok = !(now > 0.95 && now < 1.55); });
  EXPECT_EQ(s, bt::Status::SUCCESS);
  EXPECT_EQ(nav.count("halt FollowPath"), 1);
  EXPECT_TRUE(nav.recoveries().empty());  // the gate waits for health on a timer, not a recovery
  EXPECT_EQ(nav.count("follow"), 2);      // restarted with a fresh plan
  const auto stop = std::find(nav.log.begin(), nav.log.end(), "Stop");
  // In the tick the sensors went silent: the gate stops the robot and halts control.
  ASSERT_GE(nav.log.end() - stop, 2);
  EXPECT_EQ(*std::next(stop), "halt FollowPath");
}

TEST_F(NavigateTreeTest, BadLocalizationForTooLongFails) {
  auto tree = load();
  EXPECT_EQ(run(tree, 30.0, [&](double now) { nav.localization_ok = now < 0.5; }), bt::Status::FAILURE);
  EXPECT_NEAR(t, 0.5 + 10.0 + 0.1, 1e-9);  // the safety gate waits 10 s for health to return
  EXPECT_EQ(nav.log.back(), "Stop");
}

TEST(BtXmlErrors, MutatedDefaultTreeNeverCrashes) {
  bt::test::Harness h;
  bt::Factory f;
  for (const auto& spec : navigation_leaf_specs())
    f.register_action(
        spec.id, [&h](const bt::NodeConfig& c) { return std::make_unique<bt::test::ScriptedAction>(c, h); },
        spec.ports);
  std::ifstream in(bipednav::test::source_dir() / "config/behavior_trees/navigate.xml");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string xml = ss.str();
  ASSERT_GT(xml.size(), 1000u);
  bt::load_tree_xml(xml, f);  // the original loads
  Rng rng(42);
  int errors = 0;
  for (int i = 0; i < 300; ++i) {
    std::string m = xml;
    const auto pos = static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(m.size()) - 1));
    switch (i % 4) {
      case 0:
        m.erase(pos, static_cast<std::size_t>(rng.uniform_int(1, 40)));
        break;
      case 1:
        m[pos] = "<>/\"={}_ aZ0"[rng.uniform_int(0, 12)];
        break;
      case 2:
        m.resize(pos);
        break;
      default:
        m.insert(pos, m.substr(static_cast<std::size_t>(rng.uniform_int(0, 2000)), 60));
        break;
    }
    try {
      auto tree = bt::load_tree_xml(m, f);
      for (int k = 0; k < 5; ++k) tree.tick(0.1 * k);
    } catch (const Error&) {
      ++errors;
    }
  }
  EXPECT_GT(errors, 100);
}

}  // namespace
}  // namespace bipednav::navigation
