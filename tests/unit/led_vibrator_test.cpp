#include "daemon/drivers/led_vibrator_actuator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "tests/fakes/fake_sysfs.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using vibscore::testing::FakeSysfs;
using vibscore::testing::TempDir;

class SysfsVibratorTest : public vibscore::testing::SysfsTreeTest {
  protected:
    std::unique_ptr<Actuator> led(std::map<std::string, std::string> settings = {}) {
        settings["sysfs-root"] = tree.path().string();
        return make_led_vibrator_actuator(settings, sysfs->attributes());
    }
    std::unique_ptr<Actuator> timed_output(std::map<std::string, std::string> settings = {}) {
        settings["sysfs-root"] = tree.path().string();
        return make_timed_output_actuator(settings, sysfs->attributes());
    }
};

// ----- led-vibrator -----

TEST_F(SysfsVibratorTest, LedOpensWithTheTransientTriggerStateAndDuration) {
    sysfs->add_led("vibrator");
    const auto vibrator = led();
    EXPECT_THAT(sysfs->writes(),
                ElementsAre("class/leds/vibrator/trigger=transient", "class/leds/vibrator/state=1",
                            "class/leds/vibrator/duration=5000"));
    EXPECT_EQ(vibrator->driver_name(), "led-vibrator");
    EXPECT_EQ(sysfs->value("class/leds/vibrator/brightness"), "0");
}

TEST_F(SysfsVibratorTest, LedIsOnOffWithTheDurationAsItsLimit) {
    sysfs->add_led("vibrator");
    const auto capabilities = led({{"duration-ms", "1500"}})->capabilities();
    EXPECT_FALSE(capabilities.amplitude_control) << "the player pulse-modulates strength";
    EXPECT_FALSE(capabilities.frequency_control);
    EXPECT_DOUBLE_EQ(capabilities.max_on_time_s, 1.5);
}

TEST_F(SysfsVibratorTest, LedApplyActivatesAndOffDeactivates) {
    sysfs->add_led("buzz");
    const auto vibrator = led({{"led", "buzz"}});
    sysfs->clear_writes();
    vibrator->apply({0.7});
    EXPECT_EQ(sysfs->value("class/leds/buzz/brightness"), "255");
    vibrator->off();
    EXPECT_EQ(sysfs->value("class/leds/buzz/brightness"), "0");
    vibrator->apply({0.3});
    vibrator->apply({0.0});
    EXPECT_THAT(sysfs->writes(),
                ElementsAre("class/leds/buzz/activate=1", "class/leds/buzz/activate=0",
                            "class/leds/buzz/activate=1", "class/leds/buzz/activate=0"));
}

TEST_F(SysfsVibratorTest, LedAmplitudeAttributeGivesAmplitudeControl) {
    sysfs->add_led("vibrator");
    sysfs->create("class/leds/vibrator/device/amplitude", "0");
    const auto vibrator = led({{"amplitude-path", "device/amplitude"}, {"amplitude-max", "100"}});
    EXPECT_TRUE(vibrator->capabilities().amplitude_control);
    sysfs->clear_writes();
    vibrator->apply({0.25});
    vibrator->apply({0.25});  // unchanged strength: no amplitude write
    vibrator->apply({1.0});
    EXPECT_THAT(
        sysfs->writes(),
        ElementsAre("class/leds/vibrator/device/amplitude=25", "class/leds/vibrator/activate=1",
                    "class/leds/vibrator/activate=1", "class/leds/vibrator/device/amplitude=100",
                    "class/leds/vibrator/activate=1"));
}

TEST_F(SysfsVibratorTest, AbsoluteAmplitudePathMustLieUnderTheSysfsRoot) {
    sysfs->add_led("vibrator");
    sysfs->create("bus/i2c/devices/1-005a/amplitude", "0");
    const auto vibrator = led({{"amplitude-path", path("bus/i2c/devices/1-005a/amplitude")}});
    vibrator->apply({1.0});
    EXPECT_EQ(sysfs->value("bus/i2c/devices/1-005a/amplitude"), "255");
    EXPECT_THAT(error_of([&] {
                    led({{"amplitude-path", "/etc/passwd"}});
                }),
                HasSubstr("amplitude-path = \"/etc/passwd\": expected an attribute under"));
    EXPECT_THAT(error_of([&] {
                    led({{"amplitude-path", "../../../../x"}});
                }),
                HasSubstr("expected an attribute under"));
}

TEST_F(SysfsVibratorTest, LedClosesOffWithItsPreviousTriggerBack) {
    sysfs->add_led("vibrator", "timer");
    auto vibrator = led();
    vibrator->apply({1.0});
    sysfs->clear_writes();
    vibrator.reset();
    EXPECT_THAT(sysfs->writes(),
                ElementsAre("class/leds/vibrator/activate=0", "class/leds/vibrator/trigger=timer"));
    EXPECT_EQ(sysfs->value("class/leds/vibrator/brightness"), "0");
}

TEST_F(SysfsVibratorTest, LedErrorsNameThePath) {
    EXPECT_THAT(error_of([&] { led(); }), HasSubstr(path("class/leds/vibrator") + ": no such LED"));
    sysfs->add_led("vibrator");
    sysfs->fail("class/leds/vibrator/trigger", EINVAL);
    EXPECT_THAT(error_of([&] { led(); }),
                HasSubstr(path("class/leds/vibrator/trigger") +
                          ": cannot write \"transient\": Invalid argument"));
    sysfs->heal();

    const auto vibrator = led();
    sysfs->fail("class/leds/vibrator/activate", ENODEV);
    EXPECT_THAT(
        error_of([&] { vibrator->apply({1.0}); }),
        HasSubstr(path("class/leds/vibrator/activate") + ": cannot write \"1\": No such device"));
    EXPECT_NO_THROW(vibrator->off());
    sysfs->heal();
    EXPECT_NO_THROW(vibrator->apply({1.0}));
}

TEST_F(SysfsVibratorTest, AFailedOpenPutsThePreviousTriggerBack) {
    sysfs->add_led("vibrator");
    sysfs->fail("class/leds/vibrator/state", EIO);
    EXPECT_THAT(error_of([&] { led(); }), HasSubstr("state: cannot write \"1\""));
    EXPECT_EQ(sysfs->writes().back(), "class/leds/vibrator/trigger=none");
}

TEST_F(SysfsVibratorTest, LedSettingsAreChecked) {
    sysfs->add_led("vibrator");
    EXPECT_THAT(error_of([&] {
                    led({{"led", "../../etc"}});
                }),
                HasSubstr("led = \"../../etc\": expected a device name"));
    EXPECT_THAT(error_of([&] { led({{"duration-ms", "0"}}); }), HasSubstr("duration-ms = \"0\""));
    EXPECT_THAT(error_of([&] {
                    led({{"amplitude-max", "10"}});
                }),
                HasSubstr("unknown led-vibrator setting amplitude-max"));
    EXPECT_THAT(error_of([&] {
                    led({{"name", "vibrator"}});
                }),
                HasSubstr("unknown led-vibrator setting name"));
    EXPECT_THAT(sysfs->writes(), IsEmpty());
}

// ----- timed-output -----

TEST_F(SysfsVibratorTest, TimedOutputWritesTheDurationToSwitchOnAndZeroToSwitchOff) {
    sysfs->add_timed_output("vibrator");
    auto vibrator = timed_output({{"duration-ms", "800"}});
    EXPECT_EQ(vibrator->driver_name(), "timed-output");
    EXPECT_FALSE(vibrator->capabilities().amplitude_control);
    EXPECT_DOUBLE_EQ(vibrator->capabilities().max_on_time_s, 0.8);
    vibrator->apply({0.4});
    vibrator->apply({0.9});
    vibrator->off();
    vibrator.reset();
    EXPECT_THAT(sysfs->writes(), ElementsAre("class/timed_output/vibrator/enable=0",
                                             "class/timed_output/vibrator/enable=800",
                                             "class/timed_output/vibrator/enable=800",
                                             "class/timed_output/vibrator/enable=0",
                                             "class/timed_output/vibrator/enable=0"));
}

TEST_F(SysfsVibratorTest, TimedOutputArmsTheKernelTimerWithTheTimeUntilTheScoreSwitchesOff) {
    sysfs->add_timed_output("vibrator");
    auto vibrator = timed_output({{"duration-ms", "800"}});
    EXPECT_TRUE(vibrator->capabilities().off_timer);
    sysfs->clear_writes();
    vibrator->set_off_timer(0.2501);
    vibrator->apply({0.4});
    vibrator->apply({0.5});  // no time given: the longest
    vibrator->set_off_timer(30.0);
    vibrator->apply({0.6});
    vibrator->set_off_timer(0.0);
    vibrator->apply({0.7});
    EXPECT_THAT(sysfs->writes(), ElementsAre("class/timed_output/vibrator/enable=251",
                                             "class/timed_output/vibrator/enable=800",
                                             "class/timed_output/vibrator/enable=800",
                                             "class/timed_output/vibrator/enable=1"));
}

TEST_F(SysfsVibratorTest, LedTakesTheTimeUntilTheScoreSwitchesOffAsItsDuration) {
    sysfs->add_led("vibrator");
    const auto vibrator = led();
    EXPECT_TRUE(vibrator->capabilities().off_timer);
    sysfs->clear_writes();
    vibrator->set_off_timer(0.3);
    vibrator->apply({0.7});
    EXPECT_THAT(sysfs->writes(),
                ElementsAre("class/leds/vibrator/duration=300", "class/leds/vibrator/activate=1"));
}

TEST_F(SysfsVibratorTest, TimedOutputAmplitudeIsRelativeToTheDevice) {
    sysfs->add_timed_output("motor");
    sysfs->create("class/timed_output/motor/amp", "0");
    const auto vibrator = timed_output({{"name", "motor"}, {"amplitude-path", "amp"}});
    EXPECT_TRUE(vibrator->capabilities().amplitude_control);
    vibrator->apply({0.5});
    EXPECT_EQ(sysfs->value("class/timed_output/motor/amp"), "128");
    EXPECT_EQ(sysfs->value("class/timed_output/motor/enable"), "5000");
}

TEST_F(SysfsVibratorTest, TimedOutputErrorsNameThePath) {
    EXPECT_THAT(
        error_of([&] { timed_output(); }),
        HasSubstr(path("class/timed_output/vibrator/enable") + ": no such timed_output device"));
    sysfs->add_timed_output("vibrator");
    const auto vibrator = timed_output();
    sysfs->fail("class/timed_output/vibrator/enable", EIO);
    EXPECT_THAT(error_of([&] { vibrator->apply({1.0}); }),
                HasSubstr(path("class/timed_output/vibrator/enable") +
                          ": cannot write \"5000\": Input/output error"));
    EXPECT_NO_THROW(vibrator->off());
}

}  // namespace
}  // namespace vibscore::drivers
