// `bipednav cloud filter|segment` and `bipednav bench perception` (the harness is bench/perception).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/commands.hpp"
#include "bench/perception.hpp"
#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/io/ply.hpp"
#include "bipednav/perception/ground_segmentation.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "bipednav/perception/voxel_grid.hpp"

namespace bipednav::app {
namespace {

namespace fs = std::filesystem;
using perception::PassThroughParams;

PointCloud read_cloud(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".ply") return io::read_ply(file);
  if (ext == ".pcd") return io::read_pcd(file);
  throw Error(file.string() + ": unknown point cloud format (expected .pcd or .ply)");
}

struct BandOptions {
  double range_m = std::numeric_limits<double>::infinity();
  double zmin = -std::numeric_limits<double>::infinity();
  double zmax = std::numeric_limits<double>::infinity();

  void add_to(CLI::App* c) {
    c->add_option("--range", range_m, "keep points within this distance of the origin [m]")->check(check::positive());
    c->add_option("--zmin", zmin, "keep points with z >= this [m]")->check(check::finite());
    c->add_option("--zmax", zmax, "keep points with z <= this [m]")->check(check::finite());
  }
  // The pass-through's parameters; throws Error naming the option at fault (--zmin above --zmax).
  PassThroughParams params() const {
    PassThroughParams p;
    p.max_range_m = range_m;
    p.min_height_m = zmin;
    p.max_height_m = zmax;
    with_flag_names({{"max_range_m", "--range"}, {"min_height_m", "--zmin"}, {"max_height_m", "--zmax"}},
                    [&] { p.validate(); });
    return p;
  }
};

struct FilterOptions {
  std::string in, out, encoding = "binary_compressed";
  double voxel_m = 0.0;
  BandOptions band;
  bool json = false;
};

void run_filter(const FilterOptions& o) {
  const io::PcdEncoding encoding = io::pcd_encoding_from_string(o.encoding);
  const PassThroughParams band = o.band.params();
  prepare_output_file(o.out, "OUT");
  const PointCloud in = read_cloud(o.in);
  const Stopwatch sw;
  PointCloud out = perception::pass_through(in, band);
  const std::size_t after_band = out.size();
  if (o.voxel_m > 0.0) {
    perception::VoxelGridParams v;
    v.leaf_size_m.setConstant(o.voxel_m);
    out = perception::voxel_downsample(out, v);
  }
  const double ms = sw.elapsed_ms();
  io::write_pcd(o.out, out, encoding);
  const bool voxel = o.voxel_m > 0.0;
  const nlohmann::json j = {{"file", o.in},
                            {"points", in.size()},
                            {"after_pass_through", after_band},
                            {"voxel_m", voxel ? nlohmann::json(o.voxel_m) : nlohmann::json(nullptr)},
                            {"after_voxel_grid", voxel ? nlohmann::json(out.size()) : nlohmann::json(nullptr)},
                            {"time_ms", ms},
                            {"out", o.out}};
  print_figures(o.json, j, [&] {
    if (voxel)
      std::printf("%s: %zu points, %zu after the pass-through, %zu after the voxel grid (%.2f ms) -> %s\n",
                  o.in.c_str(), in.size(), after_band, out.size(), ms, o.out.c_str());
    else
      std::printf("%s: %zu points, %zu after the pass-through, no voxel grid (%.2f ms) -> %s\n", o.in.c_str(),
                  in.size(), after_band, ms, o.out.c_str());
  });
}

struct SegmentOptions {
  std::string in;
  perception::RansacParams ransac;
  std::uint64_t seed = 1;
  bool json = false;
  BandOptions band;
};

// Returns whether a plane was found (the exit status).
bool run_segment(SegmentOptions o) {
  with_flag_names({{"distance_threshold_m", "--threshold"},
                   {"success_probability", "--probability"},
                   {"max_iterations", "--max-iterations"}},
                  [&] { o.ransac.validate(); });
  const PointCloud in = perception::pass_through(read_cloud(o.in), o.band.params());
  Rng rng(o.seed);
  const Stopwatch sw;
  const perception::PlaneFit fit = perception::fit_plane_ransac(in.points, o.ransac, rng);
  const double ms = sw.elapsed_ms();
  nlohmann::json j;
  j["file"] = o.in;
  j["found"] = fit.found;
  j["plane"] = {fit.plane[0], fit.plane[1], fit.plane[2], fit.plane[3]};
  j["inliers"] = fit.inliers;
  j["points"] = in.size();
  j["distance_threshold_m"] = o.ransac.distance_threshold_m;
  j["inlier_std_m"] = fit.inlier_std_m;
  j["iterations"] = fit.iterations;
  j["time_ms"] = ms;
  print_figures(o.json, j, [&] {
    if (!fit.found)
      std::printf("no plane found in %s (%zu points after the filter)\n", o.in.c_str(), in.size());
    else
      std::printf("plane %.6f %.6f %.6f %.6f, %zu of %zu points within %.3f m, %.2f ms\n", fit.plane[0], fit.plane[1],
                  fit.plane[2], fit.plane[3], fit.inliers, in.size(), o.ransac.distance_threshold_m, ms);
  });
  return fit.found;
}

void add_filter(CLI::App& cloud) {
  auto o = std::make_shared<FilterOptions>();
  CLI::App* c = cloud.add_subcommand("filter", "Pass-through / range filter and voxel grid; writes a PCD");
  c->add_option("IN", o->in, "input cloud (.pcd or .ply)")->required()->check(CLI::ExistingFile);
  c->add_option("OUT", o->out, "output .pcd")->required();
  c->add_option("--voxel", o->voxel_m, "voxel leaf size [m] (0: no voxel grid)")
      ->capture_default_str()
      ->check(check::non_negative());
  o->band.add_to(c);
  c->add_option("--encoding", o->encoding, "ascii, binary or binary_compressed")
      ->capture_default_str()
      ->check(CLI::IsMember({"ascii", "binary", "binary_compressed"}));
  add_json_flag(c, o->json);
  c->callback([o] { run_filter(*o); });
}

void add_segment(CLI::App& cloud) {
  auto o = std::make_shared<SegmentOptions>();
  CLI::App* c = cloud.add_subcommand("segment", "RANSAC plane fit (eq. 4.1-4.4)");
  c->add_option("IN", o->in, "input cloud (.pcd or .ply)")->required()->check(CLI::ExistingFile);
  c->add_option("--threshold", o->ransac.distance_threshold_m, "inlier distance [m]")
      ->capture_default_str()
      ->check(check::positive());
  c->add_option("--probability", o->ransac.success_probability, "desired success probability (eq. 4.4)")
      ->capture_default_str()
      ->check(check::open_range(0.0, 1.0));
  c->add_option("--max-iterations", o->ransac.max_iterations, "cap on the iteration count")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  c->add_flag("--normal-prior", o->ransac.use_normal_prior, "only accept planes within 15 deg of horizontal");
  c->add_option("--seed", o->seed, "RANSAC seed, a whole number >= 0")
      ->capture_default_str()
      ->check(check::integer_at_least(0));
  o->band.add_to(c);
  add_json_flag(c, o->json);
  c->callback([o] { report_task(run_segment(*o)); });
}

// Prints the figures; returns whether the benchmark met its goals (the exit status).
bool bench_perception(const bench::PerceptionBenchOptions& o) {
  const nlohmann::json j = bench::run_perception_bench(o);
  print_json(j);
  return bench_goals_met(j);
}

void add_perception_bench(CLI::App& bench) {
  auto o = std::make_shared<bench::PerceptionBenchOptions>();
  CLI::App* c = bench.add_subcommand("perception", "Voxel grid, RANSAC and the Digit frame pipeline timings");
  c->add_option("--reps", o->reps, "repetitions per figure (median reported)")
      ->capture_default_str()
      ->check(check::integer_in(1, 1000));
  accept_json_flag(c);
  c->callback([o] { report_task(bench_perception(*o)); });
}

}  // namespace

void add_cloud_commands(CLI::App& app, CLI::App& bench) {
  CLI::App* cloud = app.add_subcommand("cloud", "Point cloud tools (filter, segment)");
  cloud->require_subcommand(1);
  add_filter(*cloud);
  add_segment(*cloud);
  add_perception_bench(bench);
}

}  // namespace bipednav::app
