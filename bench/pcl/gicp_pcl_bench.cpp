// Side-by-side GICP on the fast_gicp scan pair: PCL's GeneralizedIterativeClosestPoint against
// bipednav::localization::gicp_align, same clouds (0.2 m voxel grid from bipednav), same initial
// guess (identity), same k = 20 covariance neighbours and 1 m correspondence distance. Prints one
// JSON object. Opt-in (-DBIPEDNAV_BENCH_PCL=ON); the goal is bipednav >= 3x faster.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "bipednav/common/clock.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/localization/gicp.hpp"
#include "bipednav/perception/voxel_grid.hpp"

namespace {

using bipednav::PointCloud;
using bipednav::SE3;

PointCloud load(const std::filesystem::path& file) {
  bipednav::perception::VoxelGridParams vp;
  vp.leaf_size_m = Eigen::Vector3d::Constant(0.2);
  return bipednav::perception::voxel_downsample(bipednav::io::read_pcd(file), vp);
}

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const PointCloud& c) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr out(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : c.points) out->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path dir = argc > 1 ? argv[1] : BIPEDNAV_DATA_DIR "/lidar/fast_gicp";
  const PointCloud target = load(dir / "251370668.pcd"), source = load(dir / "251371071.pcd");
  const auto pt = to_pcl(target), ps = to_pcl(source);
  std::vector<double> pcl_ms, ours_ms;
  Eigen::Matrix4f pcl_T = Eigen::Matrix4f::Identity();
  SE3 ours_T = SE3::Identity();
  for (int rep = 0; rep < 3; ++rep) {
    bipednav::Stopwatch sw;
    pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
    gicp.setCorrespondenceRandomness(20);
    gicp.setMaxCorrespondenceDistance(1.0);
    gicp.setInputSource(ps);
    gicp.setInputTarget(pt);
    pcl::PointCloud<pcl::PointXYZ> aligned;
    gicp.align(aligned);
    pcl_ms.push_back(sw.elapsed_ms());
    pcl_T = gicp.getFinalTransformation();
    const bipednav::localization::GicpResult r = bipednav::localization::gicp_align(source, target, SE3::Identity());
    ours_ms.push_back(r.time_ms);
    ours_T = r.T_target_source;
  }
  const double pcl = median(pcl_ms), ours = median(ours_ms);
  nlohmann::json j = {
      {"source_points", source.size()},
      {"target_points", target.size()},
      {"pcl_gicp_ms", pcl},
      {"bipednav_gicp_ms", ours},
      {"speedup_vs_pcl_ratio", pcl / ours},
      {"goal_speedup_vs_pcl_ratio", 3.0},
      {"meets_goal_speedup_vs_pcl", pcl / ours >= 3.0},
      {"translation_difference_m", (pcl_T.block<3, 1>(0, 3).cast<double>() - ours_T.translation()).norm()}};
  std::printf("%s\n", j.dump(2).c_str());
  return 0;
}
