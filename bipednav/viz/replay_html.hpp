#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav::viz {

using Outline = std::vector<Eigen::Vector2d>;  // a closed polygon, world or body frame

// A costmap at one moment: cells row-major, row 0 at origin_y_m, costmap_2d values (0 free,
// 1..252 inflated, 253 inscribed, 254 lethal, 255 unknown).
struct ReplayGrid {
  double t_s = 0.0;
  int width = 0, height = 0;
  double resolution_m = 0.05, origin_x_m = 0.0, origin_y_m = 0.0;
  std::vector<std::uint8_t> cells;
};

// A moving obstacle: its top-view outline in its own frame (posed by ReplayFrame::actors).
struct ReplayActor {
  std::string name;
  std::vector<Outline> outlines;
};

struct ReplayGoal {
  double t_s = 0.0;  // when it was given
  Pose2 pose;
};

// A placed or planned foot of a humanoid footstep run: its sole centre and the kind of the action
// that puts it there (planar, t_step, step_over, step_onto, step_down; empty for the start feet).
struct ReplayFoot {
  double t_s = 0.0;  // when it landed (taken feet)
  bool left = true;
  Pose2 pose;
  std::string action;
};

// The footstep layer of a humanoid run: the feet taken, the navigator's heightmap as it fills in.
struct ReplayFootsteps {
  double foot_length_m = 0.16, foot_width_m = 0.09;
  std::vector<ReplayFoot> taken;  // sorted by time: the start feet, then every landed foot
  // Heights quantised to cells 0..254 from height_lo_m to height_hi_m, 255 unobserved.
  std::vector<ReplayGrid> height_maps;
  double height_lo_m = 0.0, height_hi_m = 0.0;
};

// One sampled moment of the run.
struct ReplayFrame {
  double t_s = 0.0;
  Pose2 true_pose, estimated_pose;
  Twist cmd;
  std::optional<Pose2> goal;  // the navigator's active goal
  Path global_path, local_trajectory;
  std::vector<Pose2> actors;                  // one per ReplayData::actors
  std::vector<Eigen::Vector2f> lidar, depth;  // latest returns, world frame
  std::string active_node;                    // the behavior tree's running leaf
  std::string state;                          // IDLE, ACTIVE, SUCCEEDED, FAILED
  std::string outcome;                        // the move_base outcome once finished
  // Footstep runs: the plan's remaining feet (from the next landing) and whether it was just made.
  std::vector<ReplayFoot> plan;
  bool replanned = false;
};

struct ReplaySummary {
  std::string scenario, robot;
  bool success = false;
  std::string outcome, message;
  double time_s = 0.0, path_length_m = 0.0, min_clearance_m = 0.0;
  int collisions = 0;
  std::size_t replans = 0, recoveries = 0;
};

// Everything the replay page shows. Grids are listed when they changed; a frame shows the
// latest grid at or before its time.
struct ReplayData {
  std::string title;
  ReplaySummary summary;
  double robot_radius_m = 0.2;
  std::vector<Outline> statics;  // static world geometry, world frame
  std::vector<ReplayActor> actors;
  std::vector<ReplayGoal> goals;
  std::vector<ReplayFrame> frames;  // sorted by time
  std::vector<ReplayGrid> global_maps, local_maps;
  std::optional<ReplayFootsteps> footsteps;  // humanoid footstep runs only
  std::string local_planner;                 // wheeled runs: the local planner that ran ("teb", "tracker")
};

struct ReplayHtmlParams {
  double position_resolution_m = 0.01;  // coordinates are rounded to this (points: int16 multiples)
  void validate() const;
};

// The page's data as JSON (the schema is documented in replay_template.html). Paths are listed
// only in frames where they changed; grid cells and points are base64 of zlib-deflated bytes.
std::string replay_json(const ReplayData& data, const ReplayHtmlParams& params = {});
// One self-contained HTML file: inline CSS and JS, the data as embedded JSON, no network access.
std::string replay_html(const ReplayData& data, const ReplayHtmlParams& params = {});
void write_replay_html(const std::filesystem::path& file, const ReplayData& data, const ReplayHtmlParams& params = {});

}  // namespace bipednav::viz
