#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "bipednav/common/rng.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/sim/fault.hpp"
#include "bipednav/sim/scenario.hpp"

namespace bipednav::sim {

// The scenario's goals with the goal floods merged in: `goal_count` goals at random places in
// the bounds spread over each flood, then the goal in force at its end is given again.
std::vector<TimedGoal> goals_with_floods(const std::vector<TimedGoal>& goals, const std::vector<Fault>& faults,
                                         const Bounds& bounds, std::uint64_t seed);

struct FaultCounters {
  std::size_t sweeps_dropped = 0, depth_points_nan = 0, odometry_jumps = 0, odometry_slipped = 0;
  std::size_t messages_delayed = 0, messages_reordered = 0;
  std::size_t commands_dropped = 0;
};

// Applies the sensor faults to each simulator frame before the navigator sees it, and the
// command faults to the navigator's commands on their way to the robot.
class FaultInjector {
 public:
  FaultInjector(std::vector<Fault> faults, std::uint64_t seed);

  SensorFrame apply(SensorFrame frame);
  // Whether any fault touches the sensor data (apply() changes nothing without one).
  bool has_sensor_faults() const;
  // Whether a velocity command sent at t_s is lost on its way to the walking controller
  // (COMMAND_DROPOUT); counts the lost ones.
  bool drops_command(double t_s);
  const FaultCounters& counters() const { return counters_; }

 private:
  bool active(FaultType type, double t_s) const;
  const Fault* find(FaultType type, double t_s) const;
  void corrupt_odometry(Odometry& odom);
  void delay(SensorFrame& frame, double delay_s);
  void reorder(SensorFrame& frame);

  std::vector<Fault> faults_;
  Rng rng_;
  FaultCounters counters_;
  // Odometry as reported: the true increments (scaled while slipping) integrated on `reported_`.
  std::optional<Pose2> last_true_odom_;
  Pose2 reported_odom_;
  std::vector<bool> jumped_;
  // Out-of-order stamps: per source, the last delivered stamp and whether the next is swapped.
  std::optional<double> last_odom_stamp_, last_sweep_stamp_;
  std::map<std::string, std::optional<double>> last_depth_stamp_;
  bool flip_odom_ = false, flip_sweep_ = false;
  std::map<std::string, bool> flip_depth_;
};

}  // namespace bipednav::sim
