#include "bipednav/control/gait_command.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::control {

void GaitCommandBuffer::send(const Twist& cmd, double stamp_s) {
  last_ = cmd;
  last_stamp_s_ = stamp_s;
  ++count_;
  if (keep_history_) history_.push_back({cmd, stamp_s});
}

void StopOnSilenceParams::validate() const {
  require(std::isfinite(timeout_s) && timeout_s > 0.0, "timeout_s", "> 0 s");
}

StopOnSilence::StopOnSilence(GaitCommandInterface& downstream, const StopOnSilenceParams& params)
    : downstream_(downstream), params_(params) {
  params_.validate();
}

void StopOnSilence::send(const Twist& cmd, double stamp_s) {
  if (!std::isfinite(stamp_s)) throw Error("StopOnSilence::send: stamp is not finite");
  last_stamp_s_ = stamp_s;
  has_command_ = true;
  stopped_ = false;
  downstream_.send(cmd.is_finite() ? cmd : Twist{}, stamp_s);
}

bool StopOnSilence::tick(double now_s) {
  if (!has_command_ || stopped_) return stopped_;
  if (now_s - last_stamp_s_ > params_.timeout_s) {
    stopped_ = true;
    downstream_.send(Twist{}, now_s);
  }
  return stopped_;
}

}  // namespace bipednav::control
