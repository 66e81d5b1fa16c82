// The LED class interface end to end, without the daemon: brightness and the transient trigger
// (Android's LED vibrator) written in sysfs, seen by a uleds LED.
#include <gtest/gtest.h>

#include <thread>

#include "tests/hil/kernel_files.hpp"
#include "tests/hil/uleds_led.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;

bool brightness_is(const BrightnessChange& change, int brightness) {
    return change.brightness == brightness;
}

TEST(LedsSmoke, BrightnessWrittenInSysfsReachesTheLed) {
    UledsLed led("vibscore-hil-led", 100);
    EXPECT_EQ(read_attribute(led.sysfs_dir() / "max_brightness"), "100");
    write_attribute(led.sysfs_dir() / "brightness", "40");
    EXPECT_TRUE(led.wait_for([](const auto& c) { return brightness_is(c, 40); }));
    write_attribute(led.sysfs_dir() / "brightness", "0");
    EXPECT_TRUE(led.wait_for([](const auto& c) { return brightness_is(c, 0); }));
    EXPECT_EQ(led.changes().size(), 2u);
}

TEST(LedsSmoke, TheTransientTriggerTurnsTheLedOnForItsDuration) {
    UledsLed led("vibrator");
    const auto dir = led.sysfs_dir();
    write_attribute(dir / "trigger", "transient");
    EXPECT_NE(read_attribute(dir / "trigger").find("[transient]"), std::string::npos);
    write_attribute(dir / "state", "1");
    write_attribute(dir / "duration", "150");
    write_attribute(dir / "activate", "1");

    ASSERT_TRUE(led.wait_for([](const auto& c) { return brightness_is(c, 255); }));
    ASSERT_TRUE(led.wait_for([](const auto& c) { return brightness_is(c, 0); }));
    const auto changes = led.changes();
    ASSERT_EQ(changes.size(), 2u);
    EXPECT_EQ(changes[0].brightness, 255);
    EXPECT_EQ(changes[1].brightness, 0);
    // The fixture's reading thread adds delay to both edges, never takes time away.
    EXPECT_GE(changes[1].time - changes[0].time, 140ms);
    EXPECT_EQ(read_attribute(dir / "activate"), "0");
}

}  // namespace
}  // namespace vibscore::hil
