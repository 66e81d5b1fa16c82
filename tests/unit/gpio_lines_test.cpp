// The part of open_gpio_lines() both libgpiod generations share, on fake chips: how a chip is
// found, which lines are refused with which message, and the order of the calls at the end.
// The libgpiod calls themselves (gpio_lines_v1.cpp, gpio_lines_v2.cpp) are tested on gpio-sim
// in the hil tier (tests/hil/gpio_lines_test.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <stdexcept>
#include <string>
#include <vector>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/gpio_lines.hpp"
#include "daemon/drivers/gpio_lines_chip.hpp"
#include "tests/fakes/fake_gpio_chip.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using vibscore::testing::FakeGpioChips;
using vibscore::testing::TempDir;

// A device directory with chips in it: each one is an entry the label search finds.
class GpioLinesTest : public ::testing::Test {
  protected:
    std::filesystem::path add(const std::string& name, FakeGpioChips::Chip chip) {
        const auto path = dev_.write(name, "");
        chips_.add(path, std::move(chip));
        return path;
    }

    std::unique_ptr<GpioLines> open(const std::string& chip, std::vector<unsigned> offsets) {
        return request_gpio_lines(chip, offsets, dev_.path(), chips_.opener());
    }

    // The DeviceError's message for opening `chip` (fails the test when it opens).
    std::string refusal(const std::string& chip, std::vector<unsigned> offsets = {0}) {
        try {
            open(chip, std::move(offsets));
        } catch (const DeviceError& error) {
            return error.what();
        }
        ADD_FAILURE() << chip << " opened";
        return "";
    }

    std::string dev(const std::string& name) const { return (dev_.path() / name).string(); }

    TempDir dev_;
    FakeGpioChips chips_;
};

// ----- finding the chip -----

TEST_F(GpioLinesTest, ANumberOpensThatGpiochipEntry) {
    add("gpiochip0", {"pinctrl"});
    add("gpiochip12", {"expander"});
    open("12", {0});
    EXPECT_EQ(chips_.calls().front(), "open " + dev("gpiochip12"));
}

TEST_F(GpioLinesTest, ANumberIsReadAsANumber) {
    add("gpiochip0", {"pinctrl"});
    add("gpiochip7", {"expander"});
    open("07", {0});
    open("000", {0});
    EXPECT_THAT(chips_.calls(), ::testing::Contains("open " + dev("gpiochip7")));
    EXPECT_THAT(chips_.calls(), ::testing::Contains("open " + dev("gpiochip0")));
    EXPECT_THAT(chips_.calls(), ::testing::Not(::testing::Contains("open " + dev("gpiochip07"))));
}

TEST_F(GpioLinesTest, AnAbsolutePathOpensThatDevice) {
    const auto path = add("gpiochip3", {"pinctrl"});
    open(path.string(), {0});
    EXPECT_EQ(chips_.calls().front(), "open " + path.string());
}

TEST_F(GpioLinesTest, ANameOpensThatEntryOfTheDeviceDirectory) {
    add("gpiochip1", {"pinctrl"});
    const auto lines = open("gpiochip1", {2});
    EXPECT_EQ(chips_.calls().front(), "open " + dev("gpiochip1"));
    EXPECT_EQ(lines->describe(), "gpiochip1 line 2");
}

TEST_F(GpioLinesTest, ALabelFindsTheChipCarryingIt) {
    add("gpiochip0", {"pinctrl-bcm2711"});
    add("gpiochip1", {"raspberrypi-exp-gpio"});
    const auto lines = open("raspberrypi-exp-gpio", {3});
    // The name was tried first, then the chips' labels in order.
    EXPECT_THAT(chips_.calls(),
                ElementsAre("open " + dev("raspberrypi-exp-gpio"), "open " + dev("gpiochip0"),
                            "open " + dev("gpiochip1"), "request 3 for vibscored"));
    EXPECT_EQ(lines->describe(), "raspberrypi-exp-gpio line 3");
}

TEST_F(GpioLinesTest, ANameWinsOverAnotherChipsLabel) {
    add("gpiochip0", {"gpiochip1"});
    add("gpiochip1", {"pinctrl"});
    const auto lines = open("gpiochip1", {0});
    EXPECT_THAT(chips_.calls(), ElementsAre("open " + dev("gpiochip1"), "request 0 for vibscored"))
        << "no label search";
}

TEST_F(GpioLinesTest, AChipThatIsNeitherANameNorALabelNamesEveryChipThere) {
    add("gpiochip0", {"pinctrl"});
    add("gpiochip1", {"expander"});
    dev_.write("gpiochip2", "");
    chips_.refuse(dev("gpiochip2"), EACCES);
    dev_.write("null", "");  // not a gpiochip* entry: not tried as a label
    EXPECT_EQ(refusal("motor-chip"),
              "GPIO chip motor-chip: no such chip: no " + dev("motor-chip") +
                  " and no chip labelled \"motor-chip\" (the chips are gpiochip0 \"pinctrl\", "
                  "gpiochip1 \"expander\", gpiochip2 cannot open: Permission denied)");
}

TEST_F(GpioLinesTest, WithoutAnyChipTheMessageSaysSo) {
    EXPECT_EQ(refusal("gpiochip0"), "GPIO chip gpiochip0: no such chip: no " + dev("gpiochip0") +
                                        " and no chip labelled \"gpiochip0\" (there is no GPIO "
                                        "chip in " +
                                        dev_.path().string() + ")");
}

TEST_F(GpioLinesTest, AMissingNumberOrPathIsNotLookedUpAsALabel) {
    add("gpiochip0", {"7"});
    EXPECT_EQ(refusal("7"),
              "GPIO chip 7: cannot open " + dev("gpiochip7") + ": No such file or directory");
    EXPECT_EQ(refusal(dev("gpiochip9")), "GPIO chip " + dev("gpiochip9") + ": cannot open " +
                                             dev("gpiochip9") + ": No such file or directory");
}

TEST_F(GpioLinesTest, AnEntryThatIsNoGpioChipIsRefusedWithTheReason) {
    dev_.write("null", "");
    chips_.refuse(dev("null"), ENOTTY);
    EXPECT_THAT(refusal("null"),
                HasSubstr("GPIO chip null: cannot open " + dev("null") + ": not a GPIO chip ("));
    dev_.write("gpiochip0", "");
    chips_.refuse(dev("gpiochip0"), EACCES);
    EXPECT_EQ(refusal("gpiochip0"),
              "GPIO chip gpiochip0: cannot open " + dev("gpiochip0") + ": Permission denied");
}

TEST_F(GpioLinesTest, AnEmptyChipNamesNoChip) {
    add("gpiochip0", {""});
    EXPECT_THAT(refusal(""), HasSubstr("an empty name names no chip"));
    EXPECT_TRUE(chips_.calls().empty());
}

// ----- the lines -----

TEST_F(GpioLinesTest, TheLastLineOfTheChipIsRequestedAndTheNextIsRefused) {
    add("gpiochip0", {"pinctrl", 4});
    EXPECT_EQ(open("gpiochip0", {3})->count(), 1u);
    EXPECT_EQ(refusal("gpiochip0", {0, 4}),
              "gpiochip0 line 4: no such line: " + dev("gpiochip0") + " has lines 0 to 3");
}

TEST_F(GpioLinesTest, AChipWithoutLinesSaysSo) {
    add("gpiochip0", {"empty", 0});
    EXPECT_THAT(refusal("gpiochip0", {0}), HasSubstr(dev("gpiochip0") + " has no lines"));
}

TEST_F(GpioLinesTest, TheLinesAreRequestedTogetherAsOutputsForVibscored) {
    add("gpiochip0", {"pinctrl", 32});
    const auto lines = open("gpiochip0", {17, 18});
    EXPECT_EQ(lines->count(), 2u);
    EXPECT_EQ(lines->describe(), "gpiochip0 lines 17, 18");
    EXPECT_THAT(chips_.calls(),
                ElementsAre("open " + dev("gpiochip0"), "request 17,18 for vibscored"));
}

TEST_F(GpioLinesTest, ABusyLineNamesWhoHoldsIt) {
    add("gpiochip0", {"pinctrl", 8, {{1, "other-app"}, {3, ""}}, EBUSY});
    EXPECT_EQ(refusal("gpiochip0", {0, 1, 3}),
              "gpiochip0 lines 0, 1, 3: cannot request as output: busy: line 1 is used by "
              "\"other-app\", line 3 is used by a consumer without a name (see gpioinfo)");
}

TEST_F(GpioLinesTest, BusyWithNoLineShownInUseGivesTheKernelsWord) {
    add("gpiochip0", {"pinctrl", 8, {}, EBUSY});
    EXPECT_EQ(refusal("gpiochip0", {2}),
              "gpiochip0 line 2: cannot request as output: Device or resource busy");
}

TEST_F(GpioLinesTest, ALineTheControllerCannotDriveGivesTheKernelsWord) {
    add("gpiochip0", {"pinctrl", 8, {{2, "not us"}}, EIO});
    EXPECT_EQ(refusal("gpiochip0", {2}),
              "gpiochip0 line 2: cannot request as output: Input/output error");
}

// ----- driving and releasing -----

TEST_F(GpioLinesTest, ValuesAreSetTogetherInRequestOrder) {
    add("gpiochip0", {"pinctrl"});
    const auto lines = open("gpiochip0", {3, 1});
    lines->set_values({1, 0});
    lines->set_values({0, 7});
    EXPECT_THAT(chips_.calls(), ElementsAre("open " + dev("gpiochip0"), "request 3,1 for vibscored",
                                            "set 1,0", "set 0,7"));
}

TEST_F(GpioLinesTest, AValueForEveryLineAndNoMore) {
    add("gpiochip0", {"pinctrl"});
    const auto lines = open("gpiochip0", {3, 1});
    EXPECT_THROW(lines->set_values({1}), std::invalid_argument);
    EXPECT_THROW(lines->set_values({1, 0, 1}), std::invalid_argument);
    EXPECT_NO_THROW(lines->set_values({1, 1}));
}

TEST_F(GpioLinesTest, AFailedSetIsADeviceErrorNamingTheLines) {
    add("gpiochip0", {"pinctrl"});
    const auto lines = open("gpiochip0", {3, 1});
    chips_.fail_sets();
    try {
        lines->set_values({1, 0});
        FAIL() << "the set succeeded";
    } catch (const DeviceError& error) {
        EXPECT_THAT(error.what(), HasSubstr("gpiochip0 lines 3, 1: cannot set values: "));
        EXPECT_THAT(error.what(), HasSubstr("Input/output error"));
    }
}

TEST_F(GpioLinesTest, TheLinesAreDrivenLowBeforeTheyAreReleased) {
    add("gpiochip0", {"pinctrl"});
    auto lines = open("gpiochip0", {0, 2});
    lines->set_values({1, 1});
    lines.reset();
    EXPECT_THAT(chips_.calls(), ElementsAre("open " + dev("gpiochip0"), "request 0,2 for vibscored",
                                            "set 1,1", "set 0,0", "release"));
}

TEST_F(GpioLinesTest, LinesThatCannotBeDrivenLowAreStillReleasedWithAWarning) {
    add("gpiochip0", {"pinctrl"});
    auto lines = open("gpiochip0", {0});
    chips_.fail_sets();
    ::testing::internal::CaptureStderr();
    lines.reset();
    const auto log = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(chips_.calls().back(), "release");
    EXPECT_THAT(log, HasSubstr("gpiochip0 line 0: cannot drive low on release: "));
}

TEST(GpioLibrary, NamesTheLibgpiodTheDaemonRunsWith) {
    EXPECT_THAT(gpio_library(), ::testing::MatchesRegex("libgpiod [12]\\.[0-9]+.*"));
}

}  // namespace
}  // namespace vibscore::drivers
