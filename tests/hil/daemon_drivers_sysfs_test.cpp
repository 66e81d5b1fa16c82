// vibscored with the sysfs backends in the guest: led-vibrator on a uleds LED with the kernel's
// transient trigger, sysfs-pwm on the pwm-sim chip through the real PWM core, and timed-output
// (no kernel has a driver for it any more) on a file tree that records every write.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "daemon/drivers/drive_levels.hpp"
#include "tests/hil/kernel_files.hpp"
#include "tests/hil/pwm_sim_chip.hpp"
#include "tests/hil/score_expectations.hpp"
#include "tests/hil/uleds_led.hpp"
#include "tests/hil/watched_playback.hpp"
#include "tests/hil/written_file.hpp"
#include "tests/support/daemon_fixture.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;
using testing::DaemonFixture;
using Clock = std::chrono::steady_clock;

const std::string kPhoneClef = "lra-phone.clef.xml";  // quarter = 0.2 s; strings 155..235 Hz

bool has(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

// An on/off actuator's expected switching: the pulse-modulated drives (docs/drivers.md).
struct Switch {
    double at;
    bool on;
};

std::vector<Switch> expected_switches(const std::string& score) {
    render::CueAdaptation adaptation;
    adaptation.amplitude = false;
    adaptation.frequency = false;
    std::vector<Switch> switches;
    for (const auto& drive : expected_drives(score, adaptation)) {
        const bool on = drive.amplitude > 0.0;
        if (switches.empty() ? on : switches.back().on != on) {
            switches.push_back({drive.at, on});
        }
    }
    return switches;
}

// Every switch at its time in the score: `seen` holds the observed on/off changes (consecutive
// repeats already merged). The observer (a watcher thread in the guest) reads some writes late
// under TCG, the first among them, so the score's time is placed where the switches put it (their
// median offset), not on the first reading alone: one late reading must not move every other.
void expect_switches(const std::vector<std::pair<Clock::time_point, bool>>& seen,
                     const std::vector<Switch>& expected, double tolerance_s,
                     const std::string& listing) {
    ASSERT_EQ(seen.size(), expected.size()) << listing;
    std::vector<double> offsets;
    for (std::size_t i = 0; i < seen.size(); ++i) {
        offsets.push_back(seconds_between(seen[0].first, seen[i].first) -
                          (expected[i].at - expected[0].at));
    }
    const double placed = median(offsets);
    for (std::size_t i = 0; i < seen.size(); ++i) {
        EXPECT_EQ(seen[i].second, expected[i].on) << "switch " << i << listing;
        EXPECT_NEAR(offsets[i], placed, tolerance_s)
            << "switch " << i << " at score time " << expected[i].at << " s" << listing;
    }
}

// The pulses of a note below full strength (expected on for less than a pulse period) last
// as long as expected: the median, since under TCG the fixtures read some edges late.
void expect_pulse_lengths(const std::vector<std::pair<Clock::time_point, bool>>& seen,
                          const std::vector<Switch>& expected, const std::string& listing) {
    std::vector<double> lengths, expected_lengths;
    for (std::size_t i = 0; i + 1 < seen.size() && i + 1 < expected.size(); ++i) {
        const double expected_s = expected[i + 1].at - expected[i].at;
        if (expected[i].on && expected_s < 0.039) {
            expected_lengths.push_back(expected_s);
            lengths.push_back(seconds_between(seen[i].first, seen[i + 1].first));
        }
    }
    ASSERT_GE(lengths.size(), 10u) << listing;
    EXPECT_NEAR(median(lengths), median(expected_lengths), 0.005) << listing;
}

// Full strength for 0.4 s, a rest, then half strength for 0.8 s: on/off actuators pulse that
// at 40 ms, on for half of each period.
const std::string kFullThenHalf =
    one_bar_score(kPhoneClef,
                  "<Note length=\"half\" number=\"9\" string=\"1\"/>"
                  "<Rest length=\"quarter\"/>"
                  "<Note length=\"whole\" number=\"4\" string=\"1\"/>");

TEST(DaemonSysfs, LedVibratorSwitchesTheLedForEachNoteAndPulsesAHalfStrengthNote) {
    UledsLed led("vibrator");
    const auto trigger = led.sysfs_dir() / "trigger";
    ASSERT_NE(read_attribute(trigger).find("[none]"), std::string::npos);
    DaemonFixture daemon(driver_config("led-vibrator", "sysfs-root = /sys\nled = vibrator"));
    EXPECT_NE(read_attribute(trigger).find("[transient]"), std::string::npos);
    EXPECT_FALSE(has(daemon.client()->Capabilities(), "amplitude-control"));
    led.clear_changes();

    const auto expected = expected_switches(kFullThenHalf);
    // The whole note at half strength is 20 pulses of 20 ms.
    ASSERT_GE(expected.size(), 40u);
    const auto played = play_to_the_end(daemon, kFullThenHalf);
    ASSERT_TRUE(played.completed);
    // The fixture's thread may not have read the last switch-off yet.
    eventually([&] { return !led.changes().empty() && led.changes().back().brightness == 0; });

    std::vector<std::pair<Clock::time_point, bool>> seen;
    std::ostringstream listing;
    for (const auto& change : led.changes()) {
        listing << "\n  " << change.time.time_since_epoch().count() / 1000
                << " us: " << change.brightness;
        const bool on = change.brightness > 0;
        if (seen.empty() ? on : seen.back().second != on) {
            seen.emplace_back(change.time, on);
        }
    }
    expect_switches(seen, expected, played.onset_tolerance_s, listing.str());
    expect_pulse_lengths(seen, expected, listing.str());
    EXPECT_EQ(led.changes().back().brightness, 0);
    for (const auto& change : led.changes()) {
        EXPECT_TRUE(change.brightness == 0 || change.brightness == 255) << change.brightness;
    }

    // Stopping the daemon gives the LED its previous trigger back.
    EXPECT_EQ(daemon.stop_daemon(), 0) << daemon.daemon_log();
    EXPECT_NE(read_attribute(trigger).find("[none]"), std::string::npos);
}

struct PwmSetting {
    std::uint64_t period_ns, duty_cycle_ns;
    bool operator==(const PwmSetting&) const = default;
};

std::ostream& operator<<(std::ostream& out, const PwmSetting& setting) {
    return out << setting.period_ns << "/" << setting.duty_cycle_ns;
}

// What the channel was set to after each drive: docs/drivers/sysfs.md's waveforms.
std::vector<std::pair<double, PwmSetting>> expected_settings(const std::vector<render::Cue>& drives,
                                                             bool lra) {
    std::vector<std::pair<double, PwmSetting>> settings;
    std::uint64_t period = 0;
    for (const auto& drive : drives) {
        if (!lra) {
            period = 50000;  // 20 kHz
        } else if (drive.amplitude > 0.0) {
            period = static_cast<std::uint64_t>(std::llround(1e9 / drive.frequency_hz));
        }
        // An LRA's drive is unipolar, at most half the period, and as wide as puts the pulses'
        // fundamental at the amplitude: (2/pi) asin(amplitude) of that half.
        const double share =
            lra ? 0.5 * drivers::lra_pulse_share(drive.amplitude) : drive.amplitude;
        const auto duty =
            static_cast<std::uint64_t>(std::llround(static_cast<double>(period) * share));
        settings.push_back({drive.at, {period, duty}});
    }
    return settings;
}

unsigned chip_number(const PwmSimChip& pwm) {
    return static_cast<unsigned>(
        std::stoul(pwm.sysfs_dir().filename().string().substr(std::string("pwmchip").size())));
}

// The channel's states while the score played, as the PWM core applied them to pwm-sim: each
// expected setting in order, every one enabled, each at its time relative to the first. A
// period change applies twice (period and duty cycle are separate attributes); the setting a
// drive asked for is the state after both.
void expect_the_channel_follows(const PwmSimChip& pwm, unsigned channel,
                                const std::vector<std::pair<double, PwmSetting>>& expected,
                                double tolerance_s) {
    std::vector<PwmApplied> applied;
    std::ostringstream listing;
    for (const auto& entry : pwm.log()) {
        if (entry.channel == channel) {
            applied.push_back(entry);
            listing << "\n  " << entry;
        }
    }
    std::size_t next = 0;
    std::optional<Clock::time_point> first;
    for (std::size_t i = 0; i < applied.size() && next < expected.size(); ++i) {
        EXPECT_TRUE(applied[i].enabled) << listing.str();
        EXPECT_LE(applied[i].duty_cycle_ns, applied[i].period_ns) << listing.str();
        const PwmSetting state{applied[i].period_ns, applied[i].duty_cycle_ns};
        if (state != expected[next].second) {
            continue;  // a step on the way (the period before the duty cycle, or the reverse)
        }
        first = first.value_or(applied[i].time);
        EXPECT_NEAR(seconds_between(*first, applied[i].time),
                    expected[next].first - expected.front().first, tolerance_s)
            << "setting " << expected[next].second << listing.str();
        ++next;
    }
    EXPECT_EQ(next, expected.size()) << "reached " << next << " of the settings" << listing.str();
}

TEST(DaemonSysfs, SysfsPwmErmSetsTheDutyCycleOfEachNoteAndZeroAfterwards) {
    PwmSimChip pwm;
    const unsigned channel = 2;
    DaemonFixture daemon(driver_config(
        "sysfs-pwm", "chip = " + std::to_string(chip_number(pwm)) + "\nchannel = 2\nmode = erm"));
    auto state = pwm.state(channel);
    EXPECT_TRUE(state.requested);
    EXPECT_TRUE(state.enabled) << "enabled from open to close";
    EXPECT_EQ(state.period_ns, 50000u);
    EXPECT_EQ(state.duty_cycle_ns, 0u);
    pwm.clear_log();

    // 1.0 for 0.2 s, a rest, 0.5 for 0.2 s.
    const auto score = one_bar_score(kPhoneClef,
                                     "<Note length=\"quarter\" number=\"9\" string=\"1\"/>"
                                     "<Rest length=\"8th\"/>"
                                     "<Note length=\"quarter\" number=\"4\" string=\"6\"/>");
    render::CueAdaptation adaptation;
    adaptation.frequency = false;
    const auto expected = expected_settings(expected_drives(score, adaptation), false);
    ASSERT_EQ(expected.size(), 4u);
    EXPECT_EQ(expected[0].second, (PwmSetting{50000, 50000}));
    EXPECT_EQ(expected[2].second, (PwmSetting{50000, 25000}));
    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    expect_the_channel_follows(pwm, channel, expected, played.onset_tolerance_s);
    EXPECT_EQ(pwm.state(channel).duty_cycle_ns, 0u);

    // Closing: duty cycle 0, disabled, and unexported since the daemon exported it.
    EXPECT_EQ(daemon.stop_daemon(), 0) << daemon.daemon_log();
    state = pwm.state(channel);
    EXPECT_FALSE(state.enabled);
    EXPECT_EQ(state.duty_cycle_ns, 0u);
    EXPECT_FALSE(state.requested);
    EXPECT_FALSE(std::filesystem::exists(pwm.sysfs_dir() / "pwm2"));
}

TEST(DaemonSysfs, SysfsPwmLraFollowsEachNotesFrequencyWithHalfThePeriodAtFullStrength) {
    PwmSimChip pwm;
    const unsigned channel = 3;
    DaemonFixture daemon(driver_config(
        "sysfs-pwm", "chip = " + std::to_string(chip_number(pwm)) + "\nchannel = 3\nmode = lra"));
    pwm.clear_log();
    // 155 Hz at full strength, then (after the separation) 235 Hz at half: the period shrinks
    // with the second note, so the order of the writes matters to the PWM core.
    const auto score = one_bar_score(kPhoneClef,
                                     "<Note length=\"quarter\" number=\"9\" string=\"1\"/>"
                                     "<Note length=\"quarter\" number=\"4\" string=\"6\"/>");
    const auto expected = expected_settings(expected_drives(score, {}), true);
    ASSERT_EQ(expected.size(), 4u);
    EXPECT_EQ(expected[0].second, (PwmSetting{6451613, 3225807}));
    // Half strength: (2/pi) asin(0.5) = 1/3 of the half period, whose fundamental is half.
    EXPECT_EQ(expected[2].second, (PwmSetting{4255319, 709220}));
    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    expect_the_channel_follows(pwm, channel, expected, played.onset_tolerance_s);
    EXPECT_EQ(daemon.stop_daemon(), 0) << daemon.daemon_log();
    EXPECT_FALSE(pwm.state(channel).enabled);
    EXPECT_FALSE(pwm.state(channel).requested);
}

TEST(DaemonSysfs, TimedOutputWritesTheOnTimeAtEachSwitchOnAndZeroAtEachSwitchOff) {
    testing::TempDir root;
    WrittenFile enable(root.path() / "class" / "timed_output" / "vibrator" / "enable", "0");
    DaemonFixture daemon(driver_config(
        "timed-output", "sysfs-root = " + root.path().string() + "\nduration-ms = 5000"));
    // Opening switches it off.
    ASSERT_TRUE(enable.wait_for([](const WrittenValue& write) { return write.value == "0"; }));
    const auto opened = enable.writes().size();

    const auto expected = expected_switches(kFullThenHalf);
    const auto played = play_to_the_end(daemon, kFullThenHalf);
    ASSERT_TRUE(played.completed);
    const double tolerance_s = played.onset_tolerance_s;
    EXPECT_EQ(daemon.stop_daemon(), 0) << daemon.daemon_log();
    // The watcher's thread reads the last switch-off on its own time, maybe after the daemon
    // has gone (as DaemonEvdev's device read its last stop after PlaybackFinished).
    EXPECT_TRUE(eventually([&] {
        const auto written = enable.writes();
        return written.size() > opened && written.back().value == "0";
    }));

    const auto writes = enable.writes();
    std::vector<std::pair<Clock::time_point, bool>> seen;
    std::vector<long> on_ms;
    std::ostringstream listing;
    for (std::size_t i = opened; i < writes.size(); ++i) {
        listing << "\n  " << writes[i].time.time_since_epoch().count() / 1000 << " us: \""
                << writes[i].value << "\"";
        const bool on = writes[i].value != "0";
        if (seen.empty() ? on : seen.back().second != on) {
            seen.emplace_back(writes[i].time, on);
            if (on) {
                on_ms.push_back(std::stol(writes[i].value));
            }
        }
    }
    listing << "\n  (the guest stalled for up to " << (tolerance_s - kOnsetTolerance_s) * 1000
            << " ms)";
    expect_switches(seen, expected, tolerance_s, listing.str());
    // Each switch-on arms the kernel's timer with the time from then until the score switches
    // off, so a killed daemon's note still ends on time: the scheduled on-time, less what the
    // switch-on was late by (at most the onset tolerance).
    std::vector<long> expected_ms;
    for (std::size_t i = 0; i + 1 < expected.size(); ++i) {
        if (expected[i].on) {
            expected_ms.push_back(std::lround((expected[i + 1].at - expected[i].at) * 1000));
        }
    }
    ASSERT_EQ(on_ms.size(), expected_ms.size()) << listing.str();
    for (std::size_t i = 0; i < on_ms.size(); ++i) {
        EXPECT_LE(on_ms[i], expected_ms[i] + 1) << "switch-on " << i << listing.str();
        EXPECT_GE(on_ms[i], expected_ms[i] - std::lround(tolerance_s * 1000))
            << "switch-on " << i << listing.str();
    }
    expect_pulse_lengths(seen, expected, listing.str());
    ASSERT_FALSE(writes.empty());
    EXPECT_EQ(writes.back().value, "0") << "off when the daemon stops";
}

}  // namespace
}  // namespace vibscore::hil
