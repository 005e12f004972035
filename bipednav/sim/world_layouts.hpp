#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/sim/world.hpp"
#include "bipednav/sim/world_generator.hpp"

// The layouts of the generated worlds (world_generator.hpp), drawn in two stages: the static
// world with start and goal (checked by the route search), then the people in it.
namespace bipednav::sim {

struct LayoutDraft {
  std::string layout;
  World world;
  Pose2 start, goal;
  // The robot's way as people should meet it: start, the door where there is one, goal.
  std::vector<Eigen::Vector2d> way;
  double fill_ratio = 0.0;  // clutter only
  // Layout-specific places the people are drawn around (the crossing corridor's or the door's centre).
  Eigen::Vector2d feature{0, 0};
  Eigen::Vector2d feature_size{0, 0};
};

// The way's length.
double way_length(const LayoutDraft& d);

// Crowd layouts (crowd_worlds.cpp): static world, then people (false when they could not be placed).
LayoutDraft draw_corridor(Rng& rng);
LayoutDraft draw_doorway(Rng& rng);
LayoutDraft draw_hall(Rng& rng);
bool add_people(LayoutDraft& d, Rng& rng, const WorldGeneratorParams& params);

// Clutter (clutter_worlds.cpp): the cellular-automaton field with `fill` of its cells filled at first.
LayoutDraft draw_clutter(Rng& rng, double fill);

}  // namespace bipednav::sim
