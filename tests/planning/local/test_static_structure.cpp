#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "bipednav/planning/local/moving_obstacles.hpp"
#include "local_test_utils.hpp"
#include "moving_obstacle_test_utils.hpp"

namespace bipednav::planning::local {

namespace {

// An occupancy grid (0.1 m cells, 12 m square around the origin) with a wall's cells lethal along
// y = wall_y from x = -3 to 6 and, when `cube` is given, the cells of a 0.5 m cube centred there
// (the global map keeps a mover's cells lethal while it is on them).
mapping::Costmap2D occupancy_with_wall(double wall_y, const std::optional<Eigen::Vector2d>& cube = std::nullopt) {
  mapping::Costmap2D m = test::empty_costmap(0.0, 0.0, 12.0, 0.1);
  const auto mark = [&](double x, double y) {
    if (const auto c = m.geometry().world_to_cell(x, y)) m.set_cost(*c, mapping::kLethal);
  };
  for (double x = -3.0; x <= 6.0; x += 0.05) mark(x, wall_y);
  if (cube) {
    for (double dx = -0.25; dx <= 0.25 + 1e-9; dx += 0.05)
      for (double dy = -0.25; dy <= 0.25 + 1e-9; dy += 0.05) mark(cube->x() + dx, cube->y() + dy);
  }
  return m;
}

// The piece of the wall along y = wall_y that a sensor sees at time t: 0.6 m of it, its start
// sliding along the wall at 1 m/s (the edge of a depth camera's view as the robot turns, or the
// gap between sparse returns at grazing incidence as it walks).
void add_wall_piece(std::vector<Eigen::Vector2d>& pts, double wall_y, double t) {
  const double a = 0.5 + 1.0 * t;
  add_wall(pts, a, a + 0.6, wall_y);
}

}  // namespace

TEST(MovingObstacles, SlidingPieceOfAWallIsNoMover) {
  // The robot walks along a wall 1 m to its left while the piece of it that it sees slides along
  // the wall: without the map that piece becomes a track moving at about 1 m/s.
  const double wall_y = 1.0;
  const mapping::Costmap2D occupancy = occupancy_with_wall(wall_y);
  MovingObstacleParams on = enabled_tracking();
  on.ignore_static_structure = true;
  MovingObstacleTracker blind(enabled_tracking()), mapped(on);
  mapped.set_static_structure(occupancy, -5.0);  // the wall has been in the map for a while
  bool blind_moving = false;
  for (int k = 0; k <= 30; ++k) {
    const double t = 0.1 * k;
    std::vector<Eigen::Vector2d> pts;
    add_wall_piece(pts, wall_y, t);
    const Pose2 robot{0.4 * t, 0.0, 0.3 * t};
    blind.update(pts, std::vector<double>(pts.size(), 2.0), robot, t);
    mapped.set_static_structure(occupancy, t);
    mapped.update(pts, std::vector<double>(pts.size(), 2.0), robot, t);
    for (const auto& m : blind.moving(t)) blind_moving = blind_moving || m.velocity.x() > 0.5;
    EXPECT_TRUE(mapped.moving(t).empty()) << "t = " << t;
  }
  EXPECT_TRUE(blind_moving);
  EXPECT_TRUE(mapped.tracks().empty());
  // Switched off (the default), the map changes nothing.
  MovingObstacleTracker unused(enabled_tracking());
  unused.set_static_structure(occupancy, -5.0);
  EXPECT_TRUE(unused.static_structure().empty());
}

TEST(MovingObstacles, CubeBesideAWallIsStillTracked) {
  // A 0.5 m cube moving at 0.3 m/s along the wall, 0.35 m from it, while the robot walks and
  // sees a sliding piece of the wall: the cube is the one moving track.
  const double wall_y = 1.0;
  const Eigen::Vector2d v(0.3, 0.0);
  MovingObstacleParams on = enabled_tracking();
  on.ignore_static_structure = true;
  MovingObstacleTracker tracker(on);
  tracker.set_static_structure(occupancy_with_wall(wall_y), -5.0);
  Eigen::Vector2d cube(-0.5, wall_y - 0.35 - 0.25);
  for (int k = 0; k <= 40; ++k) {
    const double t = 0.1 * k;
    cube = Eigen::Vector2d(-0.5, wall_y - 0.6) + v * t;
    std::vector<Eigen::Vector2d> pts;
    add_wall_piece(pts, wall_y, t);
    add_square(pts, cube, 0.5, k);
    const Pose2 robot{0.4 * t, 0.0, 0.0};
    tracker.set_static_structure(occupancy_with_wall(wall_y, cube), t);  // the map has the cube where it is
    tracker.update(pts, std::vector<double>(pts.size(), 0.5), robot, t);
  }
  const auto moving = tracker.moving(4.0);
  ASSERT_EQ(moving.size(), 1u);
  EXPECT_LT((moving[0].position - cube).norm(), 0.05);
  EXPECT_NEAR(moving[0].velocity.x(), v.x(), 0.05);
  EXPECT_NEAR(moving[0].velocity.y(), v.y(), 0.05);
}

}  // namespace bipednav::planning::local
