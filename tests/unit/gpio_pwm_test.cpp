#include "daemon/drivers/gpio_pwm_actuator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "daemon/drivers/drive_levels.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "tests/fakes/fake_gpio_lines.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using vibscore::testing::all_low;
using vibscore::testing::ends_low;
using vibscore::testing::FakeGpio;
using vibscore::testing::GpioRecord;
using vibscore::testing::median_duty;
using vibscore::testing::rising_edges;

// How far the median duty of the recorded periods may be from the intended one on a loaded test
// machine. Generous: this checks the logic (which edge when), not the timing (pwm_bench).
constexpr double kDutyTolerance = 0.1;

// ----- waveforms: exact, no thread -----

TEST(ErmWaveform, HighForDutyFromThePeriodStart) {
    const auto waveform = erm_waveform(0.25, 1000.0, false);
    EXPECT_EQ(waveform.period_ns, 1'000'000);
    EXPECT_THAT(waveform.edges, ElementsAre(PwmEdge{0, {1}}, PwmEdge{250'000, {0}}));
}

TEST(ErmWaveform, EnableLineHighThroughoutWhileDriving) {
    const auto waveform = erm_waveform(0.5, 200.0, true);
    EXPECT_EQ(waveform.period_ns, 5'000'000);
    EXPECT_THAT(waveform.edges, ElementsAre(PwmEdge{0, {1, 1}}, PwmEdge{2'500'000, {0, 1}}));
}

TEST(ErmWaveform, ZeroIsOffAndFullIsSteadyHigh) {
    EXPECT_EQ(erm_waveform(0.0, 1000.0, true), PwmWaveform{});
    const auto full = erm_waveform(1.0, 1000.0, true);
    EXPECT_TRUE(full.steady());
    EXPECT_THAT(full.edges, ElementsAre(PwmEdge{0, {1, 1}}));
}

TEST(LraWaveform, AntiphaseHalvesEachAPulseWhoseFundamentalIsTheAmplitude) {
    // sin(pi d / 2) = 0.5: d = 1/3 of each 5 ms half.
    const auto waveform = lra_waveform(0.5, 100.0, false);
    EXPECT_EQ(waveform.period_ns, 10'000'000);
    EXPECT_THAT(waveform.edges,
                ElementsAre(PwmEdge{0, {1, 0}}, PwmEdge{1'666'667, {0, 0}},
                            PwmEdge{5'000'000, {0, 1}}, PwmEdge{6'666'667, {0, 0}}));
    EXPECT_DOUBLE_EQ(lra_pulse_share(0.5), 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(lra_pulse_share(-1.0), 1.0);
    EXPECT_DOUBLE_EQ(lra_pulse_share(0.0), 0.0);
    EXPECT_NEAR(std::sin(std::numbers::pi * lra_pulse_share(0.3) / 2.0), 0.3, 1e-12);
}

TEST(LraWaveform, FullDutyAlternatesWithoutAGap) {
    const auto waveform = lra_waveform(1.0, 200.0, true);
    EXPECT_THAT(waveform.edges, ElementsAre(PwmEdge{0, {1, 0, 1}}, PwmEdge{2'500'000, {0, 1, 1}}));
}

TEST(LraWaveform, NeverBothHighAtAnyDuty) {
    for (int step = 0; step <= 100; ++step) {
        const auto waveform = lra_waveform(step / 100.0, 175.0, true);
        for (const auto& edge : waveform.edges) {
            EXPECT_FALSE(edge.values[0] == 1 && edge.values[1] == 1) << "duty " << step;
            EXPECT_EQ(edge.values[2], 1);
        }
        EXPECT_TRUE(step == 0 ? waveform == PwmWaveform{} : waveform.edges.size() >= 2);
    }
}

TEST(ErmWaveform, BackwardsRaisesTheDirectionLineThroughout) {
    const auto waveform = erm_waveform(-0.25, 1000.0, true, true);
    EXPECT_THAT(waveform.edges, ElementsAre(PwmEdge{0, {1, 1, 1}}, PwmEdge{250'000, {0, 1, 1}}));
    EXPECT_THAT(erm_waveform(0.25, 1000.0, false, true).edges,
                ElementsAre(PwmEdge{0, {1, 0}}, PwmEdge{250'000, {0, 0}}));
    EXPECT_THAT(erm_waveform(-1.0, 1000.0, false, true).edges, ElementsAre(PwmEdge{0, {1, 1}}));
}

TEST(ErmWaveform, WithoutADirectionLineBackwardsIsOff) {
    EXPECT_EQ(erm_waveform(-0.5, 1000.0, true), PwmWaveform{});
    EXPECT_EQ(erm_waveform(-1e-12, 1000.0, true, true), PwmWaveform{});
}

TEST(LraWaveform, AntiPhaseIsTheSameDriveHalfAPeriodOn) {
    const auto waveform = lra_waveform(-0.5, 100.0, false);
    EXPECT_THAT(waveform.edges,
                ElementsAre(PwmEdge{0, {0, 1}}, PwmEdge{1'666'667, {0, 0}},
                            PwmEdge{5'000'000, {1, 0}}, PwmEdge{6'666'667, {0, 0}}));
    EXPECT_THAT(lra_waveform(-1.0, 200.0, true).edges,
                ElementsAre(PwmEdge{0, {0, 1, 1}}, PwmEdge{2'500'000, {1, 0, 1}}));
    for (int step = 1; step <= 100; ++step) {
        for (const auto& edge : lra_waveform(-step / 100.0, 175.0, false).edges) {
            EXPECT_FALSE(edge.values[0] == 1 && edge.values[1] == 1) << "duty " << step;
        }
    }
}

// ----- settings -----

struct OpenedLines {
    std::string chip;
    std::vector<unsigned> offsets;
};

class GpioSettingsTest : public ::testing::Test {
  protected:
    GpioLinesOpener opener() {
        return [this](const std::string& chip, const std::vector<unsigned>& offsets) {
            opened.push_back({chip, offsets});
            return gpio->lines(offsets, chip);
        };
    }
    std::shared_ptr<FakeGpio> gpio = std::make_shared<FakeGpio>();
    std::vector<OpenedLines> opened;
};

TEST_F(GpioSettingsTest, ErmOpensItsLineOnTheDefaultChip) {
    const auto erm = make_gpio_erm_actuator({{"line", "17"}, {"rt-priority", "0"}}, opener());
    ASSERT_EQ(opened.size(), 1u);
    EXPECT_EQ(opened[0].chip, "gpiochip0");
    EXPECT_THAT(opened[0].offsets, ElementsAre(17u));
    EXPECT_EQ(erm->driver_name(), "gpio-erm");
    const auto capabilities = erm->capabilities();
    EXPECT_TRUE(capabilities.amplitude_control);
    EXPECT_FALSE(capabilities.frequency_control);
    EXPECT_FALSE(capabilities.envelopes);
}

TEST_F(GpioSettingsTest, EnableLineComesLast) {
    make_gpio_erm_actuator(
        {{"chip", "/dev/gpiochip2"}, {"line", "4"}, {"enable-line", "9"}, {"carrier-hz", "20000"}},
        opener());
    make_gpio_lra_actuator({{"line-a", "1"}, {"line-b", "2"}, {"enable-line", "3"}}, opener());
    ASSERT_EQ(opened.size(), 2u);
    EXPECT_EQ(opened[0].chip, "/dev/gpiochip2");
    EXPECT_THAT(opened[0].offsets, ElementsAre(4u, 9u));
    EXPECT_THAT(opened[1].offsets, ElementsAre(1u, 2u, 3u));
}

TEST_F(GpioSettingsTest, LraControlsAmplitudeAndFrequency) {
    const auto lra = make_gpio_lra_actuator({{"line-a", "1"}, {"line-b", "2"}}, opener());
    EXPECT_EQ(lra->driver_name(), "gpio-lra");
    EXPECT_TRUE(lra->capabilities().amplitude_control);
    EXPECT_TRUE(lra->capabilities().frequency_control);
    EXPECT_TRUE(lra->capabilities().reverse);  // its H-bridge drives in anti-phase
}

TEST_F(GpioSettingsTest, AnErmDrivesBackwardsOnlyWithADirectionLineAfterItsMotorLine) {
    EXPECT_FALSE(make_gpio_erm_actuator({{"line", "4"}}, opener())->capabilities().reverse);
    const auto erm = make_gpio_erm_actuator(
        {{"line", "4"}, {"direction-line", "5"}, {"enable-line", "9"}}, opener());
    EXPECT_TRUE(erm->capabilities().reverse);
    EXPECT_THAT(opened.back().offsets, ElementsAre(4u, 5u, 9u));
    try {
        make_gpio_erm_actuator({{"line", "4"}, {"direction-line", "4"}}, opener());
        ADD_FAILURE() << "one line twice";
    } catch (const SettingError& error) {
        EXPECT_EQ(error.key(), "direction-line");
    }
    // gpio-lra's lines already are an H-bridge: no direction line there.
    EXPECT_THROW(make_gpio_lra_actuator({{"line-a", "1"}, {"line-b", "2"}, {"direction-line", "3"}},
                                        opener()),
                 SettingError);
}

TEST_F(GpioSettingsTest, BadSettingsNameTheKey) {
    const auto message = [this](const std::map<std::string, std::string>& settings, bool lra) {
        try {
            lra ? make_gpio_lra_actuator(settings, opener())
                : make_gpio_erm_actuator(settings, opener());
        } catch (const std::invalid_argument& error) {
            return std::string(error.what());
        }
        return std::string("<no error>");
    };
    EXPECT_THAT(message({}, false), HasSubstr("gpio-erm setting line is missing"));
    EXPECT_THAT(message({{"line-a", "1"}}, true), HasSubstr("gpio-lra setting line-b is missing"));
    EXPECT_THAT(message({{"line-b", "2"}}, true), HasSubstr("gpio-lra setting line-a is missing"));
    // A misspelt key is the mistake to report, with the key it most likely meant.
    EXPECT_THAT(message({{"lines", "17"}}, false),
                HasSubstr("unknown gpio-erm setting lines = \"17\" (did you mean line?)"));
    EXPECT_THAT(message({{"line-a", "1"}, {"lineb", "2"}}, true),
                HasSubstr("unknown gpio-lra setting lineb = \"2\" (did you mean line-b?)"));
    EXPECT_THAT(message({{"line", "1"}, {"carrier-hz", "5"}}, false),
                HasSubstr("carrier-hz = \"5\""));
    EXPECT_THAT(message({{"line", "-1"}}, false), HasSubstr("line = \"-1\""));
    EXPECT_THAT(message({{"line", "3"}, {"enable-line", "3"}}, false), HasSubstr("line 3 twice"));
    EXPECT_THAT(message({{"line-a", "1"}, {"line-b", "1"}}, true), HasSubstr("line 1 twice"));
    EXPECT_THAT(message({{"line", "1"}, {"resonance-hz", "175"}}, false),
                HasSubstr("unknown gpio-erm setting resonance-hz"));
    EXPECT_THAT(message({{"line", "1"}, {"rt-priority", "100"}}, false),
                HasSubstr("rt-priority = \"100\""));
    EXPECT_TRUE(opened.empty()) << "no line is requested for a bad configuration";
}

TEST_F(GpioSettingsTest, LineRequestFailureIsADeviceError) {
    const GpioLinesOpener busy =
        [](const std::string& chip,
           const std::vector<unsigned>& offsets) -> std::unique_ptr<GpioLines> {
        throw DeviceError(describe_lines(chip, offsets) +
                          ": cannot request as output: Device or resource busy");
    };
    EXPECT_THROW(make_gpio_erm_actuator({{"line", "5"}}, busy), DeviceError);
}

// ----- playing through the PWM thread on fake lines -----

GpioPwmSettings erm_settings(double carrier_hz, bool enable_line) {
    return {GpioPwmKind::erm, carrier_hz, enable_line, /*rt_priority=*/50};
}

GpioPwmSettings lra_settings(double resonance_hz, bool enable_line) {
    return {GpioPwmKind::lra, resonance_hz, enable_line, /*rt_priority=*/50};
}

// Waits until `line` has risen `count` more times than it had in `before`.
bool wait_for_rises(FakeGpio& gpio, std::size_t line, std::size_t count) {
    const std::size_t before = rising_edges(gpio.records(), line);
    return gpio.wait_until([&](const auto& r) { return rising_edges(r, line) >= before + count; });
}

// The records from the first one at or after `from`.
std::vector<GpioRecord> records_since(const FakeGpio& gpio, std::size_t from) {
    auto records = gpio.records();
    records.erase(records.begin(), records.begin() + static_cast<std::ptrdiff_t>(from));
    return records;
}

TEST(GpioErm, DutyFollowsTheAmplitude) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator erm(erm_settings(100.0, false), gpio->lines({17}));
    for (const double amplitude : {0.25, 0.75}) {
        erm.apply({amplitude});
        // Skip the period in which the change happened, then measure 20 whole ones.
        ASSERT_TRUE(wait_for_rises(*gpio, 0, 2));
        const std::size_t from = gpio->records().size() - 1;
        ASSERT_TRUE(wait_for_rises(*gpio, 0, 20));
        EXPECT_NEAR(median_duty(records_since(*gpio, from), 0), amplitude, kDutyTolerance);
    }
}

TEST(GpioErm, EnableLineIsHighWhileDrivingAndLowWhenOff) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator erm(erm_settings(200.0, true), gpio->lines({17, 5}));
    erm.apply({0.5});
    ASSERT_TRUE(wait_for_rises(*gpio, 0, 5));
    erm.off();
    ASSERT_TRUE(gpio->wait_until(ends_low));
    const auto records = gpio->records();
    EXPECT_EQ(rising_edges(records, 1), 1u) << "the enable line rose once and stayed up";
    for (std::size_t i = 0; i + 1 < records.size(); ++i) {
        EXPECT_EQ(records[i].values[1], 1) << "record " << i;
    }
}

TEST(GpioErm, FullAmplitudeIsSteadyHighAndZeroIsOff) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator erm(erm_settings(1000.0, true), gpio->lines({17, 5}));
    erm.apply({1.0});
    ASSERT_TRUE(gpio->wait_for_records(1));
    erm.apply({0.0});
    ASSERT_TRUE(gpio->wait_for_records(2));
    const auto records = gpio->records();
    EXPECT_EQ(records[0].values, (std::vector<int>{1, 1}));
    EXPECT_EQ(records[1].values, (std::vector<int>{0, 0}));
}

TEST(GpioErm, ApplyHandsOverAndReturnsWithoutTouchingTheLines) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator erm(erm_settings(1000.0, false), gpio->lines({17}));
    for (int i = 1; i <= 50; ++i) {
        erm.apply({i / 100.0});
    }
    ASSERT_TRUE(wait_for_rises(*gpio, 0, 3));
    erm.off();
    ASSERT_TRUE(gpio->wait_until(ends_low));
    for (const auto& record : gpio->records()) {
        EXPECT_NE(record.thread, std::this_thread::get_id());
    }
}

TEST(GpioErm, LinesAreLowAfterDestruction) {
    auto gpio = std::make_shared<FakeGpio>();
    {
        GpioPwmActuator erm(erm_settings(500.0, true), gpio->lines({17, 5}));
        erm.apply({0.6});
        ASSERT_TRUE(wait_for_rises(*gpio, 0, 3));
    }
    EXPECT_TRUE(all_low(gpio->records().back()));
    EXPECT_TRUE(gpio->released());
}

TEST(GpioErm, ALineErrorFailsTheNextApplyNamingChipAndLine) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator erm(erm_settings(1000.0, false), gpio->lines({17}, "gpiochip3"));
    gpio->fail();
    // The PWM thread meets the error on its own time: applies (alternating, so each is a change)
    // until one reports it.
    std::string message;
    int attempt = 0;
    EXPECT_TRUE(vibscore::testing::wait_until([&] {
        try {
            erm.apply({0.1 + (attempt++ % 2) * 0.5});
        } catch (const DeviceError& error) {
            message = error.what();
        }
        return !message.empty();
    }));
    EXPECT_THAT(message, HasSubstr("gpio-erm on gpiochip3 line 17"));
    EXPECT_THAT(message, HasSubstr("Input/output error"));

    // The daemon goes on: once the line works again, so does the actuator.
    gpio->heal();
    erm.off();
    erm.apply({0.5});
    EXPECT_TRUE(wait_for_rises(*gpio, 0, 3));
}

TEST(GpioLra, AntiphaseNeverBothHighAndEachLineHalfTheDuty) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator lra(lra_settings(50.0, true), gpio->lines({1, 2, 3}));
    lra.apply({0.6});
    ASSERT_TRUE(wait_for_rises(*gpio, 0, 2));
    const std::size_t from = gpio->records().size() - 1;
    ASSERT_TRUE(wait_for_rises(*gpio, 0, 12));
    lra.off();
    ASSERT_TRUE(gpio->wait_until(ends_low));

    const auto records = gpio->records();
    int last_high = -1;  // A and B take turns
    for (std::size_t i = 0; i < records.size(); ++i) {
        const auto& values = records[i].values;
        EXPECT_FALSE(values[0] == 1 && values[1] == 1) << "record " << i;
        if (values[0] == 1 || values[1] == 1) {
            const int high = values[0] == 1 ? 0 : 1;
            EXPECT_NE(high, last_high) << "record " << i;
            last_high = high;
            EXPECT_EQ(values[2], 1) << "enable while driving, record " << i;
        }
    }
    // Each line high for (2/pi) asin(0.6) = 0.41 of its half period: 0.2 of the period.
    const auto measured = records_since(*gpio, from);
    const double share = lra_pulse_share(0.6) / 2.0;
    EXPECT_NEAR(median_duty(measured, 0), share, kDutyTolerance);
    EXPECT_NEAR(median_duty(measured, 1), share, kDutyTolerance);
}

TEST(GpioErm, DrivenBackwardsTheDirectionLineIsHighWhileTheMotorLinePulses) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmSettings settings = erm_settings(200.0, false);
    settings.direction_line = true;
    GpioPwmActuator erm(settings, gpio->lines({17, 18}));
    erm.apply({-0.5});
    ASSERT_TRUE(wait_for_rises(*gpio, 0, 3));
    erm.off();
    ASSERT_TRUE(gpio->wait_until(ends_low));
    const auto records = gpio->records();
    for (std::size_t i = 0; i + 1 < records.size(); ++i) {
        EXPECT_EQ(records[i].values[1], 1) << "record " << i;
    }
}

TEST(GpioLra, AntiPhaseStartsWithLineB) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator lra(lra_settings(50.0, false), gpio->lines({1, 2}));
    lra.apply({-1.0});
    ASSERT_TRUE(gpio->wait_for_records(1));
    EXPECT_EQ(gpio->records().front().values, (std::vector<int>{0, 1}));
}

TEST(GpioLra, FrequencyComesFromTheDriveOrTheResonance) {
    auto gpio = std::make_shared<FakeGpio>();
    GpioPwmActuator lra(lra_settings(50.0, false), gpio->lines({1, 2}));
    const auto mean_period_ms = [&] {
        EXPECT_TRUE(wait_for_rises(*gpio, 0, 2));  // the new period has begun
        const std::size_t from = gpio->records().size() - 1;
        EXPECT_TRUE(wait_for_rises(*gpio, 0, 10));
        const auto rises = vibscore::testing::rise_times(records_since(*gpio, from), 0);
        return static_cast<double>(rises.back() - rises.front()) / 1e6 /
               static_cast<double>(rises.size() - 1);
    };
    lra.apply({1.0, 0.0});  // the resonance: 20 ms
    const double resonance_ms = mean_period_ms();
    lra.apply({1.0, 100.0});  // 10 ms
    const double driven_ms = mean_period_ms();
    EXPECT_NEAR(resonance_ms, 20.0, 4.0);
    EXPECT_NEAR(driven_ms, 10.0, 2.0);
}

}  // namespace
}  // namespace vibscore::drivers
