#pragma once

#include <string>

#include "bipednav/common/pose2.hpp"
#include "bipednav/io/param_reader.hpp"

namespace bipednav::sim {

// Faults injected between the simulator and the navigator (the sensor path and the goal
// stream); the simulated world itself stays the ground truth.
enum class FaultType {
  LIDAR_DROPOUT,            // no LiDAR sweeps during the fault
  DEPTH_NAN_BURST,          // a share of every depth cloud's points become NaN
  LOCALIZATION_JUMP,        // the odometry pose jumps by `jump` at start_s (an estimator reset)
  ODOMETRY_SLIP,            // odometry reports `slip_scale` times the true motion
  STALE_TIMESTAMPS,         // sensor data arrives stamped `delay_s` in the past
  OUT_OF_ORDER_TIMESTAMPS,  // every second message of a source is stamped before the previous one
  GOAL_FLOOD,               // `goal_count` random goals, then the scenario's goal again
  COMMAND_DROPOUT,          // the walking controller receives no velocity commands during the fault
};

// Throws Error for an unknown name (the message lists the known ones).
FaultType fault_type_from_name(const std::string& name);

struct Fault {
  FaultType type = FaultType::LIDAR_DROPOUT;
  double start_s = 0.0;
  double duration_s = 1.0;  // ignored by LOCALIZATION_JUMP (a step)
  double nan_fraction = 1.0;
  Pose2 jump{0.3, 0.0, 0.0};
  double slip_scale = 0.5;
  double delay_s = 1.0;
  int goal_count = 20;

  bool active_at(double t_s) const { return t_s >= start_s && t_s < start_s + duration_s; }
  double end_s() const { return start_s + duration_s; }
  void validate() const;
};

// One `faults:` entry of a scenario file, e.g. {type: lidar_dropout, start_s: 8, duration_s: 3}.
Fault read_fault(io::ParamReader& r);
// "type:start_s:duration_s[:value]" from the command line (value = the type's parameter:
// nan_fraction, slip_scale, delay_s, goal_count or "dx,dy,dyaw" for the jump).
Fault parse_fault(const std::string& spec);

}  // namespace bipednav::sim
