#include "apps/cli_inflation.hpp"

#include "apps/cli_checks.hpp"

namespace bipednav::app {

void InflationFlags::add_to(CLI::App* c) {
  c->add_option("--inscribed-radius", inscribed_radius_m, "Inscribed radius of the robot, m (cost 253 within it)")
      ->capture_default_str()
      ->check(check::non_negative());
  c->add_option("--inflation-radius", inflation_radius_m, "Costs fall to 0 beyond this distance from an obstacle, m")
      ->capture_default_str()
      ->check(check::non_negative());
  c->add_option("--cost-scaling", cost_scaling, "Decay rate of the cost beyond the inscribed radius, 1/m")
      ->capture_default_str()
      ->check(check::non_negative());
  c->add_option("--unknown", unknown, "Cost of unknown cells: free | unknown | lethal")
      ->capture_default_str()
      ->check(CLI::IsMember({"free", "unknown", "lethal"}));
}

mapping::GlobalCostmapParams InflationFlags::params(double resolution_m) const {
  mapping::GlobalCostmapParams p;
  p.inscribed_radius_m = inscribed_radius_m;
  p.inflation_radius_m = inflation_radius_m;
  p.cost_scaling_factor = cost_scaling;
  p.unknown_cost_mode = unknown;
  p.resolution_m = resolution_m;
  with_flag_names({{"inscribed_radius_m", "--inscribed-radius"},
                   {"inflation_radius_m", "--inflation-radius"},
                   {"cost_scaling_factor", "--cost-scaling"},
                   {"unknown_cost_mode", "--unknown"}},
                  [&] { p.validate(); });
  return p;
}

}  // namespace bipednav::app
