// bipednav vs PCL on the same clouds: voxel grid (pcl::VoxelGrid) and RANSAC plane fitting
// (pcl::SACSegmentation, SACMODEL_PLANE, SAC_RANSAC, same threshold and success probability).
// Prints one JSON object with the median thread CPU times (the two libraries alternate rep by rep),
// the output quality and the speed ratios.
// Usage: bipednav_bench_pcl [DATA_DIR] [REPS]   (DATA_DIR holds pcl/*.pcd; default: tests/data)
#include <pcl/ModelCoefficients.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/synthetic_scene.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/perception/ground_segmentation.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "bipednav/perception/voxel_grid.hpp"

namespace {

using bipednav::PointCloud;
namespace perception = bipednav::perception;

// Thread CPU time: the machine may be shared, and both libraries run on one core here.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

// Median times of `ours` and `theirs`, run alternately (rep r of each back to back), so a busy
// machine slows both alike.
std::pair<double, double> median_ms(int reps, const std::function<void(int)>& ours,
                                    const std::function<void(int)>& theirs) {
  std::vector<double> a, b;
  for (int r = 0; r < reps; ++r) {
    double t0 = thread_cpu_ms();
    ours(r);
    a.push_back(thread_cpu_ms() - t0);
    t0 = thread_cpu_ms();
    theirs(r);
    b.push_back(thread_cpu_ms() - t0);
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return {a[a.size() / 2], b[b.size() / 2]};
}

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const PointCloud& c) {
  auto out = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  out->reserve(c.size());
  for (const auto& p : c.points) out->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  out->is_dense = false;
  return out;
}

nlohmann::json voxel(const PointCloud& c, double leaf, int reps) {
  const auto pc = to_pcl(c);
  std::size_t ours = 0, theirs = 0;
  perception::VoxelGridParams v;
  v.leaf_size_m.setConstant(leaf);
  const auto run_pcl = [&](int) {
    pcl::VoxelGrid<pcl::PointXYZ> g;
    g.setInputCloud(pc);
    g.setLeafSize(static_cast<float>(leaf), static_cast<float>(leaf), static_cast<float>(leaf));
    pcl::PointCloud<pcl::PointXYZ> out;
    g.filter(out);
    theirs = out.size();
  };
  // One-shot (a new filter and output per call, as PCL), then one VoxelGrid and output kept across
  // calls, as the perception pipeline holds them.
  const auto [ours_ms, pcl_ms] = median_ms(
      reps, [&](int) { ours = perception::voxel_downsample(c, v).size(); }, run_pcl);
  perception::VoxelGrid grid(v);
  PointCloud out;
  const auto [reused_ms, pcl2_ms] = median_ms(
      reps, [&](int) { grid.filter(c, out); }, run_pcl);
  return {{"points", c.size()},
          {"leaf_m", leaf},
          {"bipednav_ms", ours_ms},
          {"pcl_ms", pcl_ms},
          {"bipednav_voxels", ours},
          {"pcl_voxels", theirs},
          {"speedup_ratio", pcl_ms / ours_ms},
          {"bipednav_reused_ms", reused_ms},
          {"speedup_ratio_reused", pcl2_ms / reused_ms},
          {"goal_speedup_ratio", 3.0},
          {"meets_goal_speedup", pcl_ms / ours_ms >= 3.0}};
}

// Inliers of a plane by pure point-plane distance, so both fits are judged the same way.
std::size_t count_within(const PointCloud& c, const Eigen::Vector4d& pl, double t) {
  std::size_t n = 0;
  for (const auto& p : c.points)
    if (p.allFinite() && std::fabs(pl.head<3>().dot(p.cast<double>()) + pl[3]) < t) ++n;
  return n;
}

nlohmann::json ransac(const PointCloud& c, double t, int reps) {
  const auto pc = to_pcl(c);
  perception::RansacParams p;
  p.distance_threshold_m = t;
  p.success_probability = 0.99;
  p.max_iterations = 1000;
  std::vector<std::size_t> q_ours, q_pcl;
  perception::RansacScratch scratch;
  const auto [ours_ms, pcl_ms] = median_ms(
      reps,
      [&](int r) {
        bipednav::Rng rng(static_cast<std::uint64_t>(r) + 1);
        q_ours.push_back(count_within(c, perception::fit_plane_ransac(c.points, p, rng, &scratch).plane, t));
      },
      [&](int) {
        pcl::SACSegmentation<pcl::PointXYZ> seg;
        seg.setOptimizeCoefficients(true);
        seg.setModelType(pcl::SACMODEL_PLANE);
        seg.setMethodType(pcl::SAC_RANSAC);
        seg.setDistanceThreshold(t);
        seg.setProbability(0.99);
        seg.setMaxIterations(1000);
        seg.setInputCloud(pc);
        pcl::PointIndices inliers;
        pcl::ModelCoefficients coeff;
        seg.segment(inliers, coeff);
        const auto& v = coeff.values;
        q_pcl.push_back(v.size() == 4 ? count_within(c, Eigen::Vector4d(v[0], v[1], v[2], v[3]), t) : 0);
      });
  std::sort(q_ours.begin(), q_ours.end());
  std::sort(q_pcl.begin(), q_pcl.end());
  const bool equal_quality = q_ours[q_ours.size() / 2] >= 0.99 * q_pcl[q_pcl.size() / 2];
  return {{"points", c.size()},
          {"distance_threshold_m", t},
          {"bipednav_ms", ours_ms},
          {"pcl_ms", pcl_ms},
          {"bipednav_median_inliers", q_ours[q_ours.size() / 2]},
          {"pcl_median_inliers", q_pcl[q_pcl.size() / 2]},
          {"equal_quality", equal_quality},
          {"speedup_ratio", pcl_ms / ours_ms},
          {"goal_speedup_ratio", 2.0},
          {"meets_goal_speedup", pcl_ms / ours_ms >= 2.0 && equal_quality}};
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string dir = argc > 1 ? argv[1] : BIPEDNAV_DATA_DIR;
    const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 15;
    const PointCloud table = bipednav::io::read_pcd(dir + "/pcl/table_scene_mug_stereo_textured.pcd");
    const PointCloud plane = bipednav::io::read_pcd(dir + "/pcl/sac_plane_test.pcd");
    perception::PassThroughParams band;
    band.min_height_m = 0.0;
    band.max_height_m = 1.5;
    const PointCloud table_band = perception::pass_through(table, band);
    const auto digit = bipednav::bench::synthetic_digit_profile();
    const auto frame = bipednav::bench::synthetic_digit_frame(digit);
    nlohmann::json j;
    j["reps"] = reps;
    j["voxel_table_scene_0.01"] = voxel(table, 0.01, reps);
    j["voxel_digit_depth_0.02"] = voxel(frame.depth.front().cloud, 0.02, reps);
    j["ransac_table_scene_0.03"] = ransac(table_band, 0.03, reps);
    j["ransac_sac_plane_test_0.03"] = ransac(plane, 0.03, reps);
    std::printf("%s\n", j.dump(2).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bipednav_bench_pcl: %s\n", e.what());
    return 1;
  }
  return 0;
}
