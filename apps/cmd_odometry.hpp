#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "bipednav/runner/recorded_odometry.hpp"

namespace bipednav::app {

// `bipednav odometry PATH ...` on a recorded sequence (KITTI folder, PCD/PLY folder, rosbag).
struct RecordedOdometryCli {
  std::string path;
  std::string format;  // empty: detected
  std::string topic;   // rosbag: the PointCloud2 topic (empty: the only one)
  std::string lidar;   // empty: hdl64 for KITTI, else vlp16
  std::string gt;      // reference poses (TUM or KITTI), LiDAR frame
  std::string method = "loam";
  std::string out;
  std::string params;           // LOAM parameters file (default: config/lidar/<lidar>.yaml)
  std::string deskew = "auto";  // auto: on unless KITTI (its sweeps are de-skewed); on; off
  std::size_t max_sweeps = 0;
  double map_voxel_m = 0.2;
  double gicp_voxel_m = 0.5;
  double rpe_distance_m = 5.0;
  bool registration_reference = false;  // also evaluate against the sweeps' direct registration
  bool json_out = false;
};

// A scenario name or .yaml is simulated; a folder or a .bag is a recording.
bool is_recording(const std::string& path);
// Adds the recording's options to the `odometry` subcommand.
void add_recorded_odometry_options(CLI::App& cmd, RecordedOdometryCli& o);
// Runs the odometry, writes poses (TUM and KITTI), the map (PCD), the plot (PNG) and run.json
// into --out; prints run.json with --json, else a summary. Returns run.json's object.
nlohmann::json run_recorded_odometry_command(const RecordedOdometryCli& o);

// The sweeps of a recording, with the format and the reference poses resolved (--gt over the
// recording's own).
runner::SweepSequence open_recording(const RecordedOdometryCli& o, std::string& format);

}  // namespace bipednav::app
