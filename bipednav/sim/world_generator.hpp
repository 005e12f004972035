#pragma once

#include <cstdint>
#include <string>

#include "bipednav/sim/scenario.hpp"

namespace bipednav::sim {

// Families of generated benchmark worlds (`bipednav bench worlds`).
// - crowd: people walking where the robot has to go, in one of three layouts drawn from the seed:
//   a corridor 1.8-3 m wide with a crossing corridor (people coming head-on, walking slowly ahead
//   of the robot, crossing), two rooms joined by a door (people walking through the door and pacing
//   in front of it), and an open hall with furniture (2-6 people on straight, pacing and looping
//   paths). People walk at 0.3-1.3 m/s and are 0.35-0.5 m wide and 1.7 m tall.
// - clutter: a field of thin posts and boxes on a lattice grown by a cellular automaton, in the
//   manner of the BARN benchmark's worlds (Perille et al. 2020), from open to very tight, between
//   walls; the robot crosses it to a goal beyond.
enum class WorldFamily { crowd, clutter };

// "crowd" | "clutter" (throws ParamError for anything else).
WorldFamily parse_world_family(const std::string& name);
const char* world_family_name(WorldFamily family);

struct WorldGeneratorParams {
  // The room the largest robot the worlds are for needs between its centre and an obstacle
  // (footprint radius + sway: Digit 0.38 m, TurtleBot3 0.2 m).
  double design_clearance_m = 0.40;
  // Crowd worlds: the static world's widest route from start to goal keeps at least
  // design_clearance_m + this from every obstacle.
  double crowd_spare_m = 0.15;
  // Clutter worlds: the same for the field's tightest passage.
  double clutter_spare_m = 0.08;
  double route_resolution_m = 0.02;  // grid of the route check (sim/route_clearance.hpp)
  // The time limit: time_limit_base_s + the route's reference length / time_limit_speed_mps.
  double time_limit_base_s = 30.0;
  double time_limit_speed_mps = 0.2;
  int max_attempts = 200;  // draws of a layout before giving up (a ParamError names the seed)

  void validate() const;
};

struct GeneratedWorld {
  Scenario scenario;                // name "<family>_<seed>": world, start, goal, bounds, 0.2 m / 0.2 rad, time limit
  std::string layout;               // corridor | doorway | hall | clutter
  double route_widest_m = 0.0;      // the static world's widest route (its centre to the obstacles)
  double reference_length_m = 0.0;  // start to goal along the layout (through the door, ...)
  int attempts = 0;                 // layouts drawn until one passed the checks
  double fill_ratio = 0.0;          // clutter: share of the lattice's cells filled
};

// The world of `seed` in `family`: the same seed gives the same world. Every world passes the
// route check above, and every person's walk keeps clear of the static obstacles, of the start and
// of the goal, and crosses or runs along the robot's way.
GeneratedWorld generate_world(WorldFamily family, std::uint64_t seed, const WorldGeneratorParams& params = {});

// The same scenario without its people (the crowd's time baseline).
Scenario without_people(Scenario scenario);

}  // namespace bipednav::sim
