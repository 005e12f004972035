#include "bipednav/sim/scenario.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/world_drawing.hpp"
#include "test_data.hpp"

namespace fs = std::filesystem;
using namespace bipednav;
using namespace bipednav::sim;

namespace {

fs::path scenario_file(const std::string& name) { return test::source_dir() / "scenarios" / (name + ".yaml"); }

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double s = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

// Distance from a point to a polygon (0 inside).
double polygon_distance(const Eigen::Vector2d& p, const Polygon2& poly) {
  bool inside = false;
  double d = 1e18;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
    d = std::min(d, segment_distance(p, a, b));
  }
  return inside ? 0.0 : d;
}

// Clearance of a point from every static footprint (below 2 m).
double clearance(const World& w, const Eigen::Vector2d& p) {
  double d = 1e18;
  for (const Geometry& g : w.statics)
    for (const Polygon2& poly : footprint(g, SE3::Identity())) d = std::min(d, polygon_distance(p, poly));
  return d;
}

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("bipednav_scenario_test_" + name);
  std::ofstream(p) << text;
  return p;
}

std::string error_of(const fs::path& file) {
  try {
    load_scenario(file);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

const std::string kMinimal = "start: [0, 0, 0]\ngoals: [{time_s: 0, pose: [1, 0, 0]}]\n";

}  // namespace

class ScenarioFile : public ::testing::TestWithParam<std::string> {};

TEST_P(ScenarioFile, LoadsValidatesAndStartAndGoalsAreClear) {
  const Scenario s = load_scenario(scenario_file(GetParam()));
  EXPECT_EQ(s.name, GetParam());
  EXPECT_NO_THROW(s.validate());
  EXPECT_FALSE(s.world.statics.empty());
  const double radius = s.robot == "digit" ? 0.35 : 0.2;  // footprint radii of the profiles
  EXPECT_GT(clearance(s.world, s.start.position()), radius + 0.1) << "start";
  for (const TimedGoal& g : s.goals) EXPECT_GT(clearance(s.world, g.pose.position()), radius + 0.1) << "goal";
  // The straight line from the start to the first goal is blocked (the robot must plan).
  const Eigen::Vector2d a = s.start.position(), b = s.goals.front().pose.position();
  double min_clear = 1e18;
  for (int i = 0; i <= 200; ++i) min_clear = std::min(min_clear, clearance(s.world, a + (b - a) * (i / 200.0)));
  if (GetParam() != "turtlebot3_world" && GetParam() != "hexagon_dynamic") {
    EXPECT_LT(min_clear, radius);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenarios, ScenarioFile,
                         ::testing::Values("hexagon_static", "hexagon_dynamic", "three_rooms", "digit_lab_static",
                                           "digit_lab_dynamic", "turtlebot3_world", "open_field"));

TEST(Scenario, HexagonStaticHasTwoGoalsAndTallCylinders) {
  const Scenario s = load_scenario(scenario_file("hexagon_static"));
  ASSERT_EQ(s.goals.size(), 2u);
  EXPECT_DOUBLE_EQ(s.goals[1].time_s, 15.0);
  EXPECT_EQ(s.goal_at(14.9), &s.goals[0]);
  EXPECT_EQ(s.goal_at(15.0), &s.goals[1]);
  int tall = 0;
  for (const Geometry& g : s.world.statics)
    if (const auto* c = std::get_if<Cylinder>(&g.shape)) tall += c->radius_m == 0.15 && c->length_m == 2.0;
  EXPECT_EQ(tall, 9);
  EXPECT_NEAR(s.bounds.min_x_m, -3.2996 - 0.5, 0.01);  // the outer wall corner plus the margin
  EXPECT_DOUBLE_EQ(s.command_at(5.0).angular_z, 0.5);
  EXPECT_DOUBLE_EQ(s.command_at(100.0).linear_x, 0.0);
}

TEST(Scenario, HexagonDynamicBoxMovesOnTheSquare) {
  const Scenario s = load_scenario(scenario_file("hexagon_dynamic"));
  ASSERT_EQ(s.world.actors.size(), 1u);
  const Actor& a = s.world.actors[0];
  const auto* box = std::get_if<Box>(&a.parts.at(0).shape);
  ASSERT_NE(box, nullptr);
  EXPECT_TRUE(box->size_m.isApprox(Eigen::Vector3d(0.15, 0.15, 2.0)));
  EXPECT_NEAR(a.trajectory.back().time_s, 4.4 / 0.25, 1e-9);  // closed square lap
  EXPECT_TRUE(a.pose_at(2.2).translation().isApprox(Eigen::Vector3d(0.55, 0.0, 0.0)));
  EXPECT_TRUE(a.pose_at(6.6 + 17.6).translation().isApprox(Eigen::Vector3d(0.0, 0.55, 0.0)));
}

TEST(Scenario, ThreeRoomsIsSixByThirtyWithMovingCubes) {
  const Scenario s = load_scenario(scenario_file("three_rooms"));
  const Bounds2 b = world_bounds(s.world);
  EXPECT_NEAR(b.max_x_m - b.min_x_m, 30.2, 1e-9);
  EXPECT_NEAR(b.max_y_m - b.min_y_m, 6.2, 1e-9);
  EXPECT_EQ(s.world.actors.size(), 3u);
  // Doorway 1 at x = 10: free between y = 0.9 and 2.3 (1.4 m).
  EXPECT_GT(clearance(s.world, {10.0, 1.6}), 0.69);
  EXPECT_LT(clearance(s.world, {10.0, 0.0}), 1e-9);
  EXPECT_EQ(s.world.statics.size(), 1u + 8u + 11u);  // ground, walls, prisms
}

TEST(Scenario, BadInputsNameFileAndField) {
  EXPECT_NE(error_of("/nonexistent/s.yaml").find("/nonexistent/s.yaml"), std::string::npos);
  const auto check = [](const std::string& tag, const std::string& yaml, const std::string& field) {
    const fs::path f = write_temp(tag + ".yaml", yaml);
    const std::string msg = error_of(f);
    EXPECT_NE(msg.find(f.string()), std::string::npos) << tag << ": " << msg;
    EXPECT_NE(msg.find(field), std::string::npos) << tag << ": " << msg;
  };
  check("unknown_key", kMinimal + "world: {}\nspeed: 3\n", "speed");
  check("unknown_nested", kMinimal + "world: {boxes: [{pose: [0, 0, 0], size_m: [1, 1, 1], colour: red}]}\n",
        "world.boxes[0].colour");
  check("wrong_type", kMinimal + "world: {}\ntime_limit_s: soon\n", "time_limit_s");
  check("nan_goal", "world: {}\nstart: [0, 0, 0]\ngoals: [{time_s: 0, pose: [.nan, 0, 0]}]\n", "goals[0].pose");
  check("short_pose", "world: {}\nstart: [0, 0]\ngoals: [{pose: [1, 0, 0]}]\n", "start");
  check("no_goals", "world: {}\nstart: [0, 0, 0]\n", "goals");
  check("no_world", kMinimal, "world");
  check("bad_world_file", kMinimal + "world_file: missing.world\n", "missing.world");
  check("bad_shape", kMinimal + "world: {moving: [{shape: cone, path: [[0, 0]]}]}\n", "world.moving[0].shape");
  check("goal_order",
        "world: {}\nstart: [0, 0, 0]\ngoals: [{time_s: 5, pose: [1, 0, 0]}, {time_s: 1, pose: [2, 0, 0]}]\n",
        "goals[1].time_s");
  check("negative_size", kMinimal + "world: {boxes: [{pose: [0, 0, 0], size_m: [1, -1, 1]}]}\n", "size_m");
  check("goal_outside_bounds", kMinimal + "world: {}\nbounds: [-1, -1, 0.5, 1]\n", "goals[0].pose");
}

TEST(Scenario, InlineWallsAndWaypointActors) {
  const fs::path f = write_temp("inline.yaml", kMinimal + R"(world:
  ground_plane: false
  walls: [{from: [0, 0], to: [4, 0], thickness_m: 0.2, height_m: 2.5}]
  moving:
    - {name: m, shape: cylinder, radius_m: 0.3, height_m: 1.0, waypoints: [[0, 0, 1, 0], [2, 2, 1, 0]], loop: false, delay_s: 1}
)");
  const Scenario s = load_scenario(f);
  ASSERT_EQ(s.world.statics.size(), 1u);
  const auto* wall = std::get_if<Box>(&s.world.statics[0].shape);
  ASSERT_NE(wall, nullptr);
  EXPECT_TRUE(wall->size_m.isApprox(Eigen::Vector3d(4.2, 0.2, 2.5)));
  EXPECT_TRUE(s.world.statics[0].T_parent_shape.translation().isApprox(Eigen::Vector3d(2, 0, 1.25)));
  const Actor& m = s.world.actors.at(0);
  EXPECT_TRUE(m.pose_at(2.0).translation().isApprox(Eigen::Vector3d(1, 1, 0)));
  EXPECT_TRUE(m.pose_at(10.0).translation().isApprox(Eigen::Vector3d(2, 1, 0)));
  EXPECT_NEAR(m.parts[0].T_parent_shape.translation().z(), 0.5, 1e-12);
}
