#include "bipednav/sim/sdf_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "bipednav/common/error.hpp"
#include "test_data.hpp"

namespace fs = std::filesystem;
using namespace bipednav;
using namespace bipednav::sim;

namespace {

fs::path turtlebot3_dir() { return test::source_dir() / "scenarios/worlds/turtlebot3"; }

const Geometry* find_geometry(const World& w, const std::string& needle) {
  for (const Geometry& g : w.statics)
    if (g.name.find(needle) != std::string::npos) return &g;
  return nullptr;
}

fs::path write_temp_world(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("bipednav_sdf_test_" + name);
  std::ofstream(p) << text;
  return p;
}

}  // namespace

TEST(SdfWorld, Turtlebot3WorldCylindersMatchGeometryMd) {
  const World w = load_sdf_world(turtlebot3_dir() / "worlds/turtlebot3_world.world");
  int cylinders = 0;
  for (const Geometry& g : w.statics) {
    const auto* c = std::get_if<Cylinder>(&g.shape);
    if (c == nullptr) continue;
    ++cylinders;
    EXPECT_NEAR(c->radius_m, 0.15, 1e-9);
    EXPECT_NEAR(c->length_m, 0.5, 1e-9);
    const Eigen::Vector3d p = g.T_parent_shape.translation();
    // On the 1.1 m grid {-1.1, 0, 1.1}^2, centre z 0.25.
    EXPECT_NEAR(std::remainder(p.x(), 1.1), 0.0, 1e-9) << g.name;
    EXPECT_NEAR(std::remainder(p.y(), 1.1), 0.0, 1e-9) << g.name;
    EXPECT_LE(std::abs(p.x()), 1.1 + 1e-9);
    EXPECT_LE(std::abs(p.y()), 1.1 + 1e-9);
    EXPECT_NEAR(p.z(), 0.25, 1e-9);
  }
  EXPECT_EQ(cylinders, 9);
  // The Fuel ground plane include becomes a plane.
  EXPECT_NE(find_geometry(w, "ground_plane"), nullptr);
}

TEST(SdfWorld, Turtlebot3WallMeshIsTheInnerHexagon) {
  const World w = load_sdf_world(turtlebot3_dir() / "worlds/turtlebot3_world.world");
  const Geometry* wall = find_geometry(w, "::body");
  ASSERT_NE(wall, nullptr);
  const auto* mesh = std::get_if<Mesh>(&wall->shape);
  ASSERT_NE(mesh, nullptr);
  std::vector<Eigen::Vector3d> pts;
  double z_min = 1e9, z_max = -1e9;
  for (const Eigen::Vector3f& v : mesh->vertices) {
    pts.push_back(wall->T_parent_shape * v.cast<double>());
    z_min = std::min(z_min, pts.back().z()), z_max = std::max(z_max, pts.back().z());
  }
  EXPECT_NEAR(z_min, -0.30, 0.01);
  EXPECT_NEAR(z_max, 0.97, 0.01);
  // Every inner corner of GEOMETRY.md is a vertex of the mesh.
  const std::vector<Eigen::Vector2d> corners{{2.933, 0},  {1.4665, 2.54},   {-1.4665, 2.54},
                                             {-2.933, 0}, {-1.4665, -2.54}, {1.4665, -2.54}};
  for (const Eigen::Vector2d& c : corners) {
    double best = 1e9;
    for (const auto& p : pts) best = std::min(best, (p.head<2>() - c).norm());
    EXPECT_LT(best, 0.005) << c.transpose();
  }
  // No vertex inside the inner hexagon (apothem 2.54, flat sides at y = +-2.54).
  for (const auto& p : pts) {
    double support = 0;
    for (int k = 0; k < 6; ++k) {
      const double a = M_PI / 2 + k * M_PI / 3;
      support = std::max(support, p.x() * std::cos(a) + p.y() * std::sin(a));
    }
    EXPECT_GT(support, 2.54 - 0.005);
  }
}

TEST(SdfWorld, Turtlebot3HeadPillarPosition) {
  const World w = load_sdf_world(turtlebot3_dir() / "worlds/turtlebot3_world.world");
  const Geometry* head = find_geometry(w, "head");
  ASSERT_NE(head, nullptr);
  const auto* mesh = std::get_if<Mesh>(&head->shape);
  ASSERT_NE(mesh, nullptr);
  double x_min = 1e9, x_max = -1e9;
  for (const Eigen::Vector3f& v : mesh->vertices) {
    const Eigen::Vector3d p = head->T_parent_shape * v.cast<double>();
    x_min = std::min(x_min, p.x()), x_max = std::max(x_max, p.x());
  }
  EXPECT_NEAR(x_min, 2.3268, 0.005);
  EXPECT_NEAR(x_max, 4.6732, 0.005);
}

// One BARN world only: libsdformat needs several seconds for each (~420 models); world_150 and
// world_299 load the same way (`bipednav sim` on them is part of the manual checks).
TEST(SdfWorld, BarnWorldLoads) {
  BIPEDNAV_REQUIRE_DATA(file, "barn/worlds/world_0.world");
  const World w = load_sdf_world(file);
  int cylinders = 0, planes = 0;
  for (const Geometry& g : w.statics) {
    if (const auto* c = std::get_if<Cylinder>(&g.shape)) {
      ++cylinders;
      EXPECT_NEAR(c->radius_m, 0.075, 1e-9);
    }
    planes += std::holds_alternative<Plane>(g.shape);
  }
  EXPECT_GT(cylinders, 100);
  EXPECT_EQ(planes, 1);
}

TEST(SdfWorld, ActorTrajectoryLoopAndDelay) {
  const fs::path file = write_temp_world("actor.world", R"(<?xml version="1.0"?>
<sdf version="1.8"><world name="w">
  <actor name="box_actor">
    <link name="body"><collision name="c"><pose>0 0 1 0 0 0</pose>
      <geometry><box><size>0.15 0.15 2.0</size></box></geometry></collision></link>
    <script><loop>true</loop><delay_start>2.0</delay_start><auto_start>true</auto_start>
      <trajectory id="0" type="square">
        <waypoint><time>0</time><pose>0 0 0 0 0 0</pose></waypoint>
        <waypoint><time>4</time><pose>2 0 0 0 0 0</pose></waypoint>
        <waypoint><time>8</time><pose>2 2 0 0 0 0</pose></waypoint>
      </trajectory></script>
  </actor>
  <actor name="walker"><skin><filename>walk.dae</filename></skin>
    <script><loop>false</loop><trajectory id="0" type="walk">
      <waypoint><time>0</time><pose>1 1 1 0 0 0</pose></waypoint>
      <waypoint><time>10</time><pose>1 6 1 0 0 0</pose></waypoint></trajectory></script>
  </actor>
</world></sdf>)");
  const World w = load_sdf_world(file);
  ASSERT_EQ(w.actors.size(), 2u);
  const Actor& a = w.actors[0];
  EXPECT_TRUE(a.loop);
  EXPECT_DOUBLE_EQ(a.delay_s, 2.0);
  ASSERT_EQ(a.trajectory.size(), 3u);
  ASSERT_EQ(a.parts.size(), 1u);
  EXPECT_NEAR(a.parts[0].T_parent_shape.translation().z(), 1.0, 1e-12);
  EXPECT_TRUE(a.pose_at(1.0).translation().isApprox(Eigen::Vector3d(0, 0, 0)));  // still waiting
  EXPECT_TRUE(a.pose_at(4.0).translation().isApprox(Eigen::Vector3d(1, 0, 0)));  // 2 s into the script
  EXPECT_TRUE(a.pose_at(8.0).translation().isApprox(Eigen::Vector3d(2, 1, 0)));
  EXPECT_TRUE(a.pose_at(12.0).translation().isApprox(Eigen::Vector3d(1, 0, 0)));  // looped: 10 s -> 2 s
  const Actor& walker = w.actors[1];
  EXPECT_FALSE(walker.loop);
  ASSERT_EQ(walker.parts.size(), 1u);
  const auto* stand_in = std::get_if<Cylinder>(&walker.parts[0].shape);
  ASSERT_NE(stand_in, nullptr);
  EXPECT_DOUBLE_EQ(stand_in->radius_m, kActorStandInRadius_m);
  // Stands on the ground: centre at 0.9 m in the world while the actor frame is at z = 1.
  EXPECT_NEAR((walker.pose_at(3.0) * walker.parts[0].T_parent_shape).translation().z(), 0.9, 1e-12);
  EXPECT_TRUE(walker.pose_at(5.0).translation().isApprox(Eigen::Vector3d(1, 3.5, 1)));
  EXPECT_TRUE(walker.pose_at(50.0).translation().isApprox(Eigen::Vector3d(1, 6, 1)));  // no loop: stays
}

TEST(SdfWorld, IncludeAndNestedPosesCompose) {
  const fs::path dir = fs::temp_directory_path() / "bipednav_sdf_models";
  fs::create_directories(dir / "post");
  std::ofstream(dir / "post/model.config") << "<?xml version='1.0'?><model><name>post</name>"
                                              "<sdf version='1.8'>model.sdf</sdf></model>";
  std::ofstream(dir / "post/model.sdf") << R"(<?xml version="1.0"?><sdf version="1.8"><model name="post">
    <static>true</static><pose>1 0 0 0 0 0</pose>
    <link name="l"><pose>0 1 0 0 0 0</pose><collision name="c"><pose>0 0 0.5 0 0 0</pose>
      <geometry><box><size>0.2 0.2 1</size></box></geometry></collision></link></model></sdf>)";
  const fs::path file = write_temp_world("include.world", R"(<?xml version="1.0"?><sdf version="1.8"><world name="w">
    <model name="group"><static>true</static><pose>10 0 0 0 0 1.5707963267948966</pose>
      <include><uri>model://post</uri><pose>1 0 0 0 0 0</pose></include></model></world></sdf>)");
  const World w = load_sdf_world(file, {dir});
  ASSERT_EQ(w.statics.size(), 1u);
  // group (10,0) yaw 90 deg * post (1,0) * link (0,1) * collision (0,0,0.5) -> (9, 1, 0.5).
  EXPECT_TRUE(w.statics[0].T_parent_shape.translation().isApprox(Eigen::Vector3d(9, 1, 0.5), 1e-9))
      << w.statics[0].T_parent_shape.translation().transpose();
}

TEST(SdfWorld, BadInputsNameTheFile) {
  EXPECT_THROW(load_sdf_world("/nonexistent/x.world"), FileError);
  const fs::path bad =
      write_temp_world("bad.world", "<sdf version='1.8'><world name='w'><model name='m'><link name='l'>");
  try {
    load_sdf_world(bad);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  const fs::path no_mesh = write_temp_world("nomesh.world", R"(<?xml version="1.0"?><sdf version="1.8"><world name="w">
    <model name="m"><static>true</static><link name="l"><collision name="c"><geometry><mesh>
    <uri>model://missing/meshes/x.dae</uri></mesh></geometry></collision></link></model></world></sdf>)");
  try {
    load_sdf_world(no_mesh);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("model://missing"), std::string::npos) << e.what();
  }
  // libsdformat throws std::invalid_argument (std::stoi) on a non-numeric version: found by fuzz_sdf_world.
  const fs::path bad_version =
      write_temp_world("badversion.world", R"(<?xml version="1.0"?><sdf version="1.x"><world name="w"></world></sdf>)");
  try {
    load_sdf_world(bad_version);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(bad_version.string()), std::string::npos) << e.what();
  }
}
