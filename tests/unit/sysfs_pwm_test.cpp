#include "daemon/drivers/sysfs_pwm_actuator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "tests/fakes/fake_gpio_lines.hpp"
#include "tests/fakes/fake_sysfs.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using vibscore::testing::FakeSysfs;
using vibscore::testing::TempDir;

TEST(KernelSysfsAttributes, WritesReplaceReadsTrimAndErrorsNameThePath) {
    TempDir tree;
    const auto attribute = tree.write("period", "1000000\n");
    const auto sysfs = make_kernel_sysfs_attributes();
    sysfs->write(attribute, "50");
    EXPECT_EQ(vibscore::testing::read_file(attribute), "50");
    EXPECT_EQ(sysfs->read(tree.write("trigger", "none [transient] timer\n")),
              "none [transient] timer");
    EXPECT_TRUE(sysfs->exists(attribute));
    EXPECT_FALSE(sysfs->exists(tree.path() / "enable"));
    EXPECT_THAT([&] { sysfs->write(tree.path() / "enable", "1"); },
                ::testing::ThrowsMessage<DeviceError>(
                    HasSubstr((tree.path() / "enable").string() +
                              ": cannot write \"1\": No such file or directory")));
    EXPECT_FALSE(sysfs->exists(tree.path() / "enable")) << "a missing attribute is not created";
    EXPECT_THAT([&] { sysfs->read(tree.path() / "duty_cycle"); },
                ::testing::ThrowsMessage<DeviceError>(
                    HasSubstr((tree.path() / "duty_cycle").string() + ": cannot read")));
}

class SysfsPwmTest : public vibscore::testing::SysfsTreeTest {
  protected:
    SysfsPwmTest() { sysfs->add_pwm_chip(0); }

    std::unique_ptr<Actuator> open(std::map<std::string, std::string> settings) {
        settings["sysfs-root"] = tree.path().string();
        return make_sysfs_pwm_actuator(settings, sysfs->attributes());
    }

    std::string open_error(std::map<std::string, std::string> settings) {
        return error_of([&] { open(std::move(settings)); });
    }
};

TEST_F(SysfsPwmTest, ExportsTheChannelThenSetsThePeriodAndEnables) {
    const auto pwm = open({{"chip", "0"}, {"channel", "1"}});
    EXPECT_THAT(sysfs->writes(),
                ElementsAre("class/pwm/pwmchip0/export=1", "class/pwm/pwmchip0/pwm1/period=50000",
                            "class/pwm/pwmchip0/pwm1/enable=1"));
    EXPECT_EQ(sysfs->value("class/pwm/pwmchip0/pwm1/duty_cycle"), "0");
    EXPECT_EQ(pwm->driver_name(), "sysfs-pwm");
}

TEST_F(SysfsPwmTest, AChannelLeftRunningIsStoppedBeforeThePeriodShrinks) {
    sysfs->add_pwm_channel(0, 0, 1'000'000, 700'000, true);
    const auto pwm = open({{"carrier-hz", "25000"}});
    EXPECT_THAT(sysfs->writes(), ElementsAre("class/pwm/pwmchip0/pwm0/duty_cycle=0",
                                             "class/pwm/pwmchip0/pwm0/period=40000",
                                             "class/pwm/pwmchip0/pwm0/enable=1"));
}

TEST_F(SysfsPwmTest, ErmDutyCycleIsAmplitudeTimesPeriod) {
    const auto pwm = open({{"carrier-hz", "1000"}});
    sysfs->clear_writes();
    pwm->apply({0.25});
    pwm->apply({0.25, 300.0});  // an ERM has no frequency to choose
    pwm->apply({1.0});
    pwm->off();
    pwm->off();
    EXPECT_THAT(sysfs->writes(), ElementsAre("class/pwm/pwmchip0/pwm0/duty_cycle=250000",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=1000000",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=0"));
    EXPECT_TRUE(pwm->capabilities().amplitude_control);
    EXPECT_FALSE(pwm->capabilities().frequency_control);
}

TEST_F(SysfsPwmTest, LraPeriodFollowsTheNoteInAnOrderTheKernelAccepts) {
    const auto pwm = open({{"mode", "lra"}, {"resonance-hz", "200"}});
    sysfs->clear_writes();
    pwm->apply({1.0, 100.0});  // longer period: period first
    pwm->apply({1.0, 250.0});  // shorter than the duty cycle: duty cycle first
    pwm->apply({0.5, 0.0});    // the resonance
    pwm->apply({0.0, 120.0});  // silence keeps the period
    EXPECT_THAT(sysfs->writes(), ElementsAre("class/pwm/pwmchip0/pwm0/period=10000000",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=5000000",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=2000000",
                                             "class/pwm/pwmchip0/pwm0/period=4000000",
                                             "class/pwm/pwmchip0/pwm0/period=5000000",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=833333",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=0"));
    EXPECT_TRUE(pwm->capabilities().frequency_control);
}

TEST_F(SysfsPwmTest, ClosingStopsDisablesAndUnexportsWhatItExported) {
    {
        const auto pwm = open({});
        pwm->apply({0.5});
        sysfs->clear_writes();
    }
    EXPECT_THAT(sysfs->writes(),
                ElementsAre("class/pwm/pwmchip0/pwm0/duty_cycle=0",
                            "class/pwm/pwmchip0/pwm0/enable=0", "class/pwm/pwmchip0/unexport=0"));
    EXPECT_FALSE(sysfs->exists("class/pwm/pwmchip0/pwm0"));
}

TEST_F(SysfsPwmTest, AChannelExportedBySomeoneElseStaysExported) {
    sysfs->add_pwm_channel(0, 0, 50'000, 0, false);
    open({}).reset();
    EXPECT_THAT(sysfs->writes(), ElementsAre("class/pwm/pwmchip0/pwm0/enable=1",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=0",
                                             "class/pwm/pwmchip0/pwm0/enable=0"));
    EXPECT_TRUE(sysfs->exists("class/pwm/pwmchip0/pwm0"));
}

TEST_F(SysfsPwmTest, TheChannelMayAppearAMomentAfterTheExport) {
    sysfs->hide_exported_channels_for(3);
    EXPECT_NO_THROW(open({}));
}

TEST_F(SysfsPwmTest, AChannelThatNeverAppearsIsAnErrorAndIsUnexported) {
    sysfs->hide_exported_channels_for(-1);
    EXPECT_THAT(open_error({}),
                HasSubstr(path("class/pwm/pwmchip0/pwm0") + ": did not appear after export"));
    EXPECT_EQ(sysfs->writes().back(), "class/pwm/pwmchip0/unexport=0");
}

TEST_F(SysfsPwmTest, OpenErrorsNameThePath) {
    EXPECT_THAT(open_error({{"chip", "3"}}),
                HasSubstr(path("class/pwm/pwmchip3") + ": no such PWM chip"));
    sysfs->fail("class/pwm/pwmchip0/export", EBUSY);
    EXPECT_THAT(open_error({}), HasSubstr(path("class/pwm/pwmchip0/export") +
                                          ": cannot write \"0\": Device or resource busy"));
}

TEST_F(SysfsPwmTest, AFailedEnableUndoesTheExport) {
    sysfs->fail("class/pwm/pwmchip0/pwm0/enable", ENODEV);
    EXPECT_THAT(open_error({}), HasSubstr("pwm0/enable: cannot write \"1\": No such device"));
    EXPECT_FALSE(sysfs->exists("class/pwm/pwmchip0/pwm0"));
}

TEST_F(SysfsPwmTest, AWriteFailureIsADeviceErrorAndTheNextDriveStartsAfresh) {
    const auto pwm = open({{"carrier-hz", "1000"}});
    sysfs->fail("class/pwm/pwmchip0/pwm0/duty_cycle", EIO);
    try {
        pwm->apply({0.5});
        FAIL() << "no DeviceError";
    } catch (const DeviceError& error) {
        EXPECT_THAT(error.what(), HasSubstr(path("class/pwm/pwmchip0/pwm0/duty_cycle") +
                                            ": cannot write \"500000\": Input/output error"));
    }
    EXPECT_NO_THROW(pwm->off()) << "off() never throws";
    sysfs->heal();
    pwm->apply({0.5});
    EXPECT_EQ(sysfs->value("class/pwm/pwmchip0/pwm0/duty_cycle"), "500000");
}

// A direction line on an H-bridge: the fake GPIO records it, the fake sysfs the duty cycle; the
// order of the two is what a bridge sees.
class SysfsPwmDirectionTest : public SysfsPwmTest {
  protected:
    std::unique_ptr<Actuator> open_with_direction(std::map<std::string, std::string> settings) {
        settings["sysfs-root"] = tree.path().string();
        return make_sysfs_pwm_actuator(
            settings, sysfs->attributes(),
            [this](const std::string& chip, const std::vector<unsigned>& offsets) {
                opened_chip = chip;
                opened_offsets = offsets;
                return gpio->lines(offsets, chip);
            });
    }
    std::shared_ptr<vibscore::testing::FakeGpio> gpio =
        std::make_shared<vibscore::testing::FakeGpio>();
    std::string opened_chip;
    std::vector<unsigned> opened_offsets;
};

TEST_F(SysfsPwmDirectionTest, ADirectionLineReversesTheDriveWithTheDutyCycleAtZero) {
    EXPECT_FALSE(open_with_direction({{"carrier-hz", "1000"}})->capabilities().reverse);
    const auto pwm = open_with_direction(
        {{"carrier-hz", "1000"}, {"direction-chip", "gpiochip3"}, {"direction-line", "7"}});
    EXPECT_EQ(opened_chip, "gpiochip3");
    EXPECT_THAT(opened_offsets, ElementsAre(7u));
    EXPECT_TRUE(pwm->capabilities().reverse);
    sysfs->clear_writes();
    pwm->apply({0.5});
    pwm->apply({-1.0});  // braking: duty 0, direction high, then full duty
    EXPECT_THAT(sysfs->writes(), ElementsAre("class/pwm/pwmchip0/pwm0/duty_cycle=500000",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=0",
                                             "class/pwm/pwmchip0/pwm0/duty_cycle=1000000"));
    ASSERT_EQ(gpio->records().size(), 1u);
    EXPECT_EQ(gpio->records()[0].values, std::vector<int>{1});
    pwm->off();  // duty 0, then the direction line low again
    EXPECT_EQ(sysfs->value("class/pwm/pwmchip0/pwm0/duty_cycle"), "0");
    ASSERT_EQ(gpio->records().size(), 2u);
    EXPECT_EQ(gpio->records()[1].values, std::vector<int>{0});
    pwm->apply({0.25});  // forwards: the line stays low
    EXPECT_EQ(gpio->records().size(), 2u);
}

TEST_F(SysfsPwmDirectionTest, WithoutADirectionLineBackwardsIsOff) {
    const auto pwm = open_with_direction({{"carrier-hz", "1000"}});
    pwm->apply({-0.5});
    EXPECT_EQ(sysfs->value("class/pwm/pwmchip0/pwm0/duty_cycle"), "0");
}

TEST_F(SysfsPwmDirectionTest, ADirectionChipWithoutALineIsAnError) {
    EXPECT_THAT(error_of([&] {
                    open_with_direction({{"direction-chip", "gpiochip1"}});
                }),
                HasSubstr("direction-chip = \"gpiochip1\" needs direction-line"));
}

TEST_F(SysfsPwmTest, SettingsAreChecked) {
    EXPECT_THAT(open_error({{"mode", "lra"}, {"carrier-hz", "1000"}}),
                HasSubstr("unknown sysfs-pwm setting carrier-hz"));
    EXPECT_THAT(open_error({{"resonance-hz", "175"}}),
                HasSubstr("unknown sysfs-pwm setting resonance-hz"));
    EXPECT_THAT(open_error({{"mode", "buzzer"}}), HasSubstr("mode = \"buzzer\""));
    EXPECT_THAT(open_error({{"channel", "x"}}), HasSubstr("channel = \"x\""));
    EXPECT_THAT(sysfs->writes(), IsEmpty()) << "a bad configuration touches nothing";
}

}  // namespace
}  // namespace vibscore::drivers
