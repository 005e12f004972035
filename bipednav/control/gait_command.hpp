#pragma once

#include <vector>

#include "bipednav/common/twist.hpp"

namespace bipednav::control {

// The interface to the walking controller (Digit's gait controller, a simulated robot model):
// a planar velocity command stamped with the (simulated) time it was issued.
class GaitCommandInterface {
 public:
  virtual ~GaitCommandInterface() = default;
  virtual void send(const Twist& cmd, double stamp_s) = 0;
};

// Keeps the latest command (and optionally all of them) for whoever drives the robot model.
class GaitCommandBuffer final : public GaitCommandInterface {
 public:
  explicit GaitCommandBuffer(bool keep_history = false) : keep_history_(keep_history) {}
  void send(const Twist& cmd, double stamp_s) override;

  const Twist& last() const { return last_; }
  double last_stamp_s() const { return last_stamp_s_; }
  int count() const { return count_; }
  struct Stamped {
    Twist cmd;
    double stamp_s;
  };
  const std::vector<Stamped>& history() const { return history_; }

 private:
  bool keep_history_;
  Twist last_;
  double last_stamp_s_ = 0.0;
  int count_ = 0;
  std::vector<Stamped> history_;
};

struct StopOnSilenceParams {
  double timeout_s = 0.5;  // longer than two periods of the 10 Hz local planner

  void validate() const;
};

// Watchdog in front of the walking controller: forwards commands (non-finite ones as zero)
// and, when no fresh command arrived within timeout_s of simulated time, sends one zero
// command so the robot stands still until commands resume.
class StopOnSilence final : public GaitCommandInterface {
 public:
  StopOnSilence(GaitCommandInterface& downstream, const StopOnSilenceParams& params = {});

  void send(const Twist& cmd, double stamp_s) override;
  // Call every control step; returns true while the watchdog holds the robot stopped.
  bool tick(double now_s);
  bool stopped() const { return stopped_; }

 private:
  GaitCommandInterface& downstream_;
  StopOnSilenceParams params_;
  double last_stamp_s_ = 0.0;
  bool has_command_ = false;
  bool stopped_ = false;
};

}  // namespace bipednav::control
