// The PWM sysfs interface end to end, without the daemon: the real PWM core's
// /sys/class/pwm files on the pwm-sim chip, and what the chip was told.
#include <gtest/gtest.h>

#include <system_error>

#include "tests/hil/kernel_files.hpp"
#include "tests/hil/pwm_sim_chip.hpp"

namespace vibscore::hil {
namespace {

TEST(PwmSmoke, ExportConfigureEnableDisableReachTheChip) {
    PwmSimChip pwm;
    ASSERT_GE(pwm.channels(), 2u);
    const auto dir = pwm.sysfs_dir();
    write_attribute(dir / "export", "1");
    const auto channel = dir / "pwm1";
    wait_for_path(channel / "enable");
    EXPECT_TRUE(pwm.state(1).requested);

    write_attribute(channel / "period", "1000000");
    write_attribute(channel / "duty_cycle", "250000");
    write_attribute(channel / "enable", "1");
    auto state = pwm.state(1);
    EXPECT_TRUE(state.enabled);
    EXPECT_EQ(state.period_ns, 1000000u);
    EXPECT_EQ(state.duty_cycle_ns, 250000u);
    EXPECT_FALSE(state.inversed);
    EXPECT_FALSE(pwm.state(0).enabled);

    write_attribute(channel / "duty_cycle", "600000");
    write_attribute(channel / "enable", "0");
    // The core applies only what changed: period and duty cycle were applied one by one before
    // the enable unless an earlier test left the channel with the same values.
    const auto log = pwm.log();
    ASSERT_GE(log.size(), 3u);
    const auto* last = &log[log.size() - 3];
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(last[i].channel, 1u);
        EXPECT_EQ(last[i].period_ns, 1000000u);
    }
    EXPECT_TRUE(last[0].enabled);
    EXPECT_EQ(last[0].duty_cycle_ns, 250000u);
    EXPECT_TRUE(last[1].enabled);
    EXPECT_EQ(last[1].duty_cycle_ns, 600000u);
    EXPECT_FALSE(last[2].enabled);
    for (std::size_t i = 1; i < log.size(); ++i) {
        EXPECT_LE(log[i - 1].time, log[i].time);
    }

    write_attribute(dir / "unexport", "1");
    EXPECT_FALSE(pwm.state(1).requested);
}

TEST(PwmSmoke, TheCoreRefusesADutyCycleLongerThanThePeriod) {
    PwmSimChip pwm;
    write_attribute(pwm.sysfs_dir() / "export", "0");
    const auto channel = pwm.sysfs_dir() / "pwm0";
    wait_for_path(channel / "enable");
    write_attribute(channel / "period", "500000");
    const auto applies = pwm.state(0).applies;
    try {
        write_attribute(channel / "duty_cycle", "600000");
        ADD_FAILURE() << "a duty cycle longer than the period was accepted";
    } catch (const std::system_error& error) {
        EXPECT_EQ(error.code().value(), EINVAL) << error.what();
    }
    EXPECT_EQ(pwm.state(0).applies, applies);
    write_attribute(channel / "polarity", "inversed");
    EXPECT_TRUE(pwm.state(0).inversed);
}

}  // namespace
}  // namespace vibscore::hil
