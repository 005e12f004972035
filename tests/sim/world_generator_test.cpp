#include "bipednav/sim/world_generator.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <variant>

#include "bipednav/common/error.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/sim/route_clearance.hpp"
#include "bipednav/sim/sdf_world.hpp"
#include "bipednav/sim/sdf_writer.hpp"
#include "bipednav/sim/simulation.hpp"
#include "bipednav/sim/world_parts.hpp"
#include "test_data.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

RobotProfile profile(const std::string& name) {
  return io::load_robot_profile(test::source_dir() / "config" / (name + ".yaml"));
}

// The static world's widest route from start to goal at 1 cm, for a robot of this height.
RouteClearance route_of(const Scenario& s, double height_m) {
  RouteClearanceParams p;
  p.height_m = height_m;
  return scenario_routes(s, p).front();
}

TEST(WorldGenerator, SameSeedSameWorld) {
  for (const WorldFamily f : {WorldFamily::crowd, WorldFamily::clutter}) {
    const GeneratedWorld a = generate_world(f, 17), b = generate_world(f, 17), c = generate_world(f, 18);
    EXPECT_EQ(sdf_world_xml(a.scenario.world), sdf_world_xml(b.scenario.world));
    EXPECT_EQ(a.scenario.start, b.scenario.start);
    EXPECT_EQ(a.scenario.goals.back().pose, b.scenario.goals.back().pose);
    EXPECT_NE(sdf_world_xml(a.scenario.world), sdf_world_xml(c.scenario.world));
    EXPECT_EQ(a.scenario.name, std::string(world_family_name(f)) + "_17");
  }
}

// Every world of the first seeds leaves both robots their room plus the spare on the static route
// (checked again here at 1 cm, with each robot's own height), and each crowd layout occurs.
TEST(WorldGenerator, EveryWorldPassesTheRouteCheck) {
  const WorldGeneratorParams params;
  std::set<std::string> layouts;
  for (const std::string robot : {"turtlebot3", "digit"}) {
    const RobotProfile r = profile(robot);
    for (std::uint64_t seed = 1; seed <= 9; ++seed) {
      const GeneratedWorld g = generate_world(WorldFamily::crowd, seed);
      layouts.insert(g.layout);
      EXPECT_GE(route_of(g.scenario, r.height_m).widest_m - needed_clearance_m(r), params.crowd_spare_m - 0.03)
          << robot << " crowd seed " << seed << " (" << g.layout << ")";
      EXPECT_GE(g.scenario.world.actors.size(), 1u);
      const GeneratedWorld c = generate_world(WorldFamily::clutter, seed);
      EXPECT_GE(route_of(c.scenario, r.height_m).widest_m - needed_clearance_m(r), params.clutter_spare_m - 0.03)
          << robot << " clutter seed " << seed;
      EXPECT_GT(c.fill_ratio, 0.0);
    }
  }
  EXPECT_EQ(layouts, (std::set<std::string>{"corridor", "doorway", "hall"}));
}

// People keep clear of the furniture and walls all along their walk, and of start and goal by
// their radius, the design clearance and 0.3 m (a robot standing there is never walked into).
TEST(WorldGenerator, PeopleWalkClearOfTheStaticWorldStartAndGoal) {
  const WorldGeneratorParams params;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const Scenario s = generate_world(WorldFamily::crowd, seed).scenario;
    const StaticClearance statics(s.world, kPersonHeight_m);
    for (const Actor& a : s.world.actors) {
      const double r = std::get<Cylinder>(a.parts.front().shape).radius_m;
      EXPECT_GE(r, 0.175);
      EXPECT_LE(r, 0.25);
      for (double t = 0.0; t < 60.0; t += 0.25) {
        const Eigen::Vector2d p = a.pose_at(t).translation().head<2>();
        ASSERT_GE(statics.at(p), r) << s.name << " " << a.name << " t=" << t;
        const double keep_off = r + params.design_clearance_m + 0.3 - 1e-9;
        EXPECT_GE((p - s.start.position()).norm(), keep_off) << s.name << " " << a.name << " t=" << t;
        EXPECT_GE((p - s.goals.back().pose.position()).norm(), keep_off) << s.name << " " << a.name << " t=" << t;
      }
    }
  }
}

TEST(WorldParts, LoopToAPointIsThePointsDistance) {
  // A back-and-forth walk along x = 2 from y = 0 to 3, and a point 0.6 m beside it.
  const std::vector<Eigen::Vector2d> walk = back_and_forth({2, 0}, {2, 3});
  EXPECT_DOUBLE_EQ(loop_to_polyline_distance(walk, {Eigen::Vector2d(1.4, 1.0)}), 0.6);
  EXPECT_DOUBLE_EQ(loop_to_polyline_distance(walk, {Eigen::Vector2d(2.0, 4.0)}), 1.0);
  EXPECT_DOUBLE_EQ(loop_to_polyline_distance(walk, {Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(1.0, 1.0)}), 1.0);
  EXPECT_DOUBLE_EQ(loop_to_polyline_distance(walk, {Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(3.0, 1.0)}), 0.0);
}

TEST(WorldGenerator, SavedWorldLoadsBackTheSame) {
  const auto dir = std::filesystem::temp_directory_path() / "bipednav_world_generator_test";
  std::filesystem::create_directories(dir);
  for (const WorldFamily f : {WorldFamily::crowd, WorldFamily::clutter}) {
    const World w = generate_world(f, 5).scenario.world;
    const auto file = dir / (w.name + ".world");
    write_sdf_world(w, file);
    const World back = load_sdf_world(file);
    ASSERT_EQ(back.statics.size(), w.statics.size() + 1);  // + the ground plane
    EXPECT_TRUE(std::holds_alternative<Plane>(back.statics.front().shape));
    for (std::size_t i = 0; i < w.statics.size(); ++i) {
      const Geometry &a = w.statics[i], &b = back.statics[i + 1];
      EXPECT_EQ(b.name.substr(0, b.name.find("::")), a.name.substr(0, a.name.find("::")));
      EXPECT_TRUE(a.T_parent_shape.isApprox(b.T_parent_shape, 1e-9)) << a.name;
      EXPECT_EQ(a.shape.index(), b.shape.index()) << a.name;
    }
    ASSERT_EQ(back.actors.size(), w.actors.size());
    for (std::size_t i = 0; i < w.actors.size(); ++i) {
      const Actor &a = w.actors[i], &b = back.actors[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.loop, b.loop);
      ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
      for (double t = 0.0; t < 30.0; t += 0.7) EXPECT_TRUE(a.pose_at(t).isApprox(b.pose_at(t), 1e-9)) << a.name;
      ASSERT_EQ(b.parts.size(), 1u);
      EXPECT_DOUBLE_EQ(std::get<Cylinder>(b.parts[0].shape).radius_m, std::get<Cylinder>(a.parts[0].shape).radius_m);
    }
  }
}

TEST(WorldGenerator, RejectsBadInput) {
  EXPECT_THROW(parse_world_family("crowds"), ParamError);
  WorldGeneratorParams p;
  p.design_clearance_m = -1.0;
  EXPECT_THROW(generate_world(WorldFamily::crowd, 1, p), ParamError);
  // A robot wider than any door cannot get a world: a clear error naming the seed, not a hang.
  p.design_clearance_m = 5.0;
  p.max_attempts = 3;
  EXPECT_THROW(generate_world(WorldFamily::crowd, 1, p), Error);
  World with_mesh;
  with_mesh.statics.push_back(Geometry{"m", SE3::Identity(), Mesh{}});
  EXPECT_THROW(sdf_world_xml(with_mesh), Error);
}

TEST(WorldGenerator, WithoutPeopleKeepsTheStaticWorld) {
  const Scenario s = generate_world(WorldFamily::crowd, 3).scenario;
  const Scenario e = without_people(s);
  EXPECT_TRUE(e.world.actors.empty());
  EXPECT_EQ(e.world.statics.size(), s.world.statics.size());
  EXPECT_EQ(e.start, s.start);
}

// A person walking into a parked robot: the contact is the person's, the robot stood still. A
// robot driving into a wall: its own.
TEST(ContactClassification, StandingRobotWalkedIntoAndMovingRobotDrivingIntoAWall) {
  World w;
  w.actors.push_back(person("walker", 0.2, back_and_forth({3.0, 0.0}, {-3.0, 0.0}), 1.0, 0.0));
  SimulationParams p;
  p.enable_lidar = p.enable_depth = false;
  Simulation parked(w, profile("turtlebot3"), Pose2{0, 0, 0}, p);
  while (!parked.first_collision() && parked.now_s() < 5.0) parked.step(Twist{});
  ASSERT_TRUE(parked.first_collision());
  EXPECT_EQ(parked.first_collision()->obstacle, "walker/body");
  EXPECT_TRUE(robot_standing(*parked.first_collision()));

  World walls;
  walls.statics.push_back(wall_segment("wall", {1.0, -2.0}, {1.0, 2.0}));
  Simulation driving(walls, profile("turtlebot3"), Pose2{0, 0, 0}, p);
  while (!driving.first_collision() && driving.now_s() < 10.0) driving.step(Twist{0.2, 0.0, 0.0});
  ASSERT_TRUE(driving.first_collision());
  EXPECT_FALSE(robot_standing(*driving.first_collision()));
  EXPECT_NEAR(driving.first_collision()->pose.x, 1.0 - 0.05 - 0.2, 0.01);
}

}  // namespace
