#include "bipednav/sim/world_generator.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/route_clearance.hpp"
#include "bipednav/sim/world_drawing.hpp"
#include "bipednav/sim/world_layouts.hpp"
#include "bipednav/sim/world_parts.hpp"

namespace bipednav::sim {
namespace {

// The clutter field's first fill: from open (few posts, wide gaps) to very tight.
constexpr double kMinFill = 0.15, kMaxFill = 0.40;
// Every this many failed clutter draws the fill drops by kFillStep (never below kFloorFill), so
// that every seed ends in a field with a passage.
constexpr int kFillRetries = 20;
constexpr double kFillStep = 0.02, kFloorFill = 0.05;

LayoutDraft draw_crowd_layout(Rng& rng, std::int64_t kind) {
  if (kind == 0) return draw_corridor(rng);
  if (kind == 1) return draw_doorway(rng);
  return draw_hall(rng);
}

Bounds bounds_of(const LayoutDraft& d) {
  Bounds2 b = world_bounds(d.world);
  b.add(d.start.position());
  b.add(d.goal.position());
  return Bounds{b.min_x_m, b.min_y_m, b.max_x_m, b.max_y_m};
}

Scenario to_scenario(WorldFamily family, std::uint64_t seed, const LayoutDraft& d, const WorldGeneratorParams& p) {
  Scenario s;
  s.name = std::string(world_family_name(family)) + "_" + std::to_string(seed);
  s.description = "generated " + d.layout + " (" + std::to_string(d.world.actors.size()) + " people)";
  s.world = d.world;
  s.world.name = s.name;
  s.start = d.start;
  s.goals = {{0.0, d.goal}};
  s.time_limit_s = std::ceil(p.time_limit_base_s + way_length(d) / p.time_limit_speed_mps);
  s.seed = seed;
  s.bounds = bounds_of(d);
  s.validate();
  return s;
}

}  // namespace

WorldFamily parse_world_family(const std::string& name) {
  if (name == "crowd") return WorldFamily::crowd;
  if (name == "clutter") return WorldFamily::clutter;
  throw ParamError("family", "crowd or clutter (got '" + name + "')");
}

const char* world_family_name(WorldFamily family) { return family == WorldFamily::crowd ? "crowd" : "clutter"; }

void WorldGeneratorParams::validate() const {
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  require(positive(design_clearance_m), "design_clearance_m", "> 0");
  require(crowd_spare_m >= 0.0 && std::isfinite(crowd_spare_m), "crowd_spare_m", ">= 0");
  require(clutter_spare_m >= 0.0 && std::isfinite(clutter_spare_m), "clutter_spare_m", ">= 0");
  require(positive(route_resolution_m) && route_resolution_m <= 0.1, "route_resolution_m", "in (0, 0.1]");
  require(time_limit_base_s >= 0.0 && std::isfinite(time_limit_base_s), "time_limit_base_s", ">= 0");
  require(positive(time_limit_speed_mps), "time_limit_speed_mps", "> 0");
  require(max_attempts >= 1, "max_attempts", ">= 1");
}

GeneratedWorld generate_world(WorldFamily family, std::uint64_t seed, const WorldGeneratorParams& p) {
  p.validate();
  // One random stream per family and seed (a multiplicative hash keeps neighbouring seeds apart).
  Rng rng(seed * 0x9E3779B97F4A7C15ULL + (family == WorldFamily::crowd ? 1 : 2));
  const bool crowd = family == WorldFamily::crowd;
  const double need_m = p.design_clearance_m + (crowd ? p.crowd_spare_m : p.clutter_spare_m);
  const std::int64_t kind = crowd ? rng.uniform_int(0, 2) : 0;
  double fill = crowd ? 0.0 : rng.uniform(kMinFill, kMaxFill);
  RouteClearanceParams route;
  route.resolution_m = p.route_resolution_m;
  route.height_m = kWallHeight_m;  // everything up to the walls' height counts, for every robot
  for (int attempt = 1; attempt <= p.max_attempts; ++attempt) {
    LayoutDraft d = crowd ? draw_crowd_layout(rng, kind) : draw_clutter(rng, fill);
    if (!crowd && attempt % kFillRetries == 0) fill = std::max(kFloorFill, fill - kFillStep);
    const Bounds b = bounds_of(d);
    const RouteClearance r = widest_route(d.world, RouteArea{{b.min_x_m, b.min_y_m}, {b.max_x_m, b.max_y_m}},
                                          d.start.position(), d.goal.position(), route);
    if (!r.connected || r.widest_m < need_m) continue;
    if (crowd && !add_people(d, rng, p)) continue;
    GeneratedWorld g;
    g.scenario = to_scenario(family, seed, d, p);
    g.layout = d.layout;
    g.route_widest_m = r.widest_m;
    g.reference_length_m = way_length(d);
    g.attempts = attempt;
    g.fill_ratio = d.fill_ratio;
    return g;
  }
  throw Error(std::string("world generator: no ") + world_family_name(family) + " world for seed " +
              std::to_string(seed) + " passed the checks in " + std::to_string(p.max_attempts) + " attempts");
}

Scenario without_people(Scenario scenario) {
  scenario.world.actors.clear();
  scenario.name += "_without_people";
  return scenario;
}

}  // namespace bipednav::sim
