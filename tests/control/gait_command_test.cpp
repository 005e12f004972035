#include "bipednav/control/gait_command.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::control {
namespace {

TEST(GaitCommand, BufferKeepsLastAndHistory) {
  GaitCommandBuffer buf(true);
  buf.send({0.1, 0, 0.2}, 1.0);
  buf.send({0.3, 0, 0}, 1.1);
  EXPECT_EQ(buf.last().linear_x, 0.3);
  EXPECT_EQ(buf.last_stamp_s(), 1.1);
  EXPECT_EQ(buf.count(), 2);
  ASSERT_EQ(buf.history().size(), 2u);
  EXPECT_EQ(buf.history()[0].cmd.angular_z, 0.2);
}

TEST(GaitCommand, StopOnSilenceZeroesAfterTimeoutOnce) {
  GaitCommandBuffer buf(true);
  StopOnSilence watchdog(buf, {0.5});
  EXPECT_FALSE(watchdog.tick(0.0));  // nothing sent yet: nothing to stop
  watchdog.send({0.3, 0, 0.1}, 1.0);
  EXPECT_FALSE(watchdog.tick(1.2));
  EXPECT_FALSE(watchdog.tick(1.5));  // exactly the timeout: still fresh
  EXPECT_TRUE(watchdog.tick(1.6));
  EXPECT_TRUE(buf.last().is_zero());
  EXPECT_EQ(buf.last_stamp_s(), 1.6);
  EXPECT_TRUE(watchdog.tick(2.0));
  EXPECT_EQ(buf.count(), 2);  // one zero command, not one per tick
  watchdog.send({0.2, 0, 0}, 2.1);
  EXPECT_FALSE(watchdog.stopped());
  EXPECT_EQ(buf.last().linear_x, 0.2);
}

TEST(GaitCommand, StopOnSilenceForwardsNonFiniteAsZero) {
  GaitCommandBuffer buf;
  StopOnSilence watchdog(buf);
  watchdog.send({std::nan(""), 0, 0.4}, 0.0);
  EXPECT_TRUE(buf.last().is_zero());
  EXPECT_THROW(watchdog.send({}, std::nan("")), Error);
  EXPECT_THROW(StopOnSilence(buf, {0.0}), ParamError);
}

}  // namespace
}  // namespace bipednav::control
