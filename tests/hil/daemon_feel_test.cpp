// The declared actuator ([actuator]) at the real kernel interfaces in the guest: the overdrive
// pulse at the start of a note and the reversed drive at its end, each as long as the actuator
// model says (daemon/render/drive_planner.*), on gpio-sim lines (gpio-erm with a direction line,
// gpio-lra's H-bridge in anti-phase), a pwm-sim channel with a direction line (sysfs-pwm), and a
// uinput force-feedback device (evdev with anti-phase). The model's constants are slow (hundreds
// of milliseconds) so that the guest's timing under TCG can show them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <thread>

#include "tests/hil/gpio_lines_sampler.hpp"
#include "tests/hil/gpio_sim_chip.hpp"
#include "tests/hil/pwm_sim_chip.hpp"
#include "tests/hil/score_expectations.hpp"
#include "tests/hil/uinput_vibrator.hpp"
#include "tests/hil/watched_playback.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;
using testing::DaemonFixture;
using Clock = std::chrono::steady_clock;

// Strength 1 for a whole note (0.8 s) on the shipped phone clef.
std::string whole_note(const std::string& string = "1") {
    return one_bar_score("lra-phone.clef.xml",
                         "<Note length=\"whole\" number=\"9\" string=\"" + string + "\"/>");
}

// An actuator braked in reverse, as the daemon's [actuator] section declares it and as the
// planner is given it: from the same numbers, so that the two cannot differ.
struct Declared {
    std::string section;
    actuator::Declaration declaration;
};

// A slow ERM: rated at half of full scale, so overdrive doubles the drive; full scale reaches
// strength 1 after 200 ms x ln 2 = 139 ms; braking backwards stops it after 200 ms x ln 1.5 =
// 81 ms.
Declared slow_erm() {
    Declared erm;
    erm.declaration.kind = actuator::Kind::erm;
    erm.declaration.rated_drive = 0.5;
    erm.declaration.spin_up_s = 0.2;
    erm.declaration.spin_down_s = 0.4;
    erm.declaration.brake = actuator::Brake::reverse;
    std::ostringstream section;
    section << "\n[actuator]\nkind = erm\nrated-drive = " << erm.declaration.rated_drive
            << "\nspin-up-ms = " << erm.declaration.spin_up_s * 1000.0
            << "\nspin-down-ms = " << erm.declaration.spin_down_s * 1000.0 << "\nbrake = reverse\n";
    erm.section = section.str();
    return erm;
}

// An LRA declared exact (tolerances 0): the plan whose brake length the kernel path must keep.
Declared exact_lra(double rated_drive, double resonance_hz, double q) {
    Declared lra;
    std::ostringstream section;
    section << "\n[actuator]\nkind = lra\nrated-drive = " << rated_drive
            << "\nresonance-hz = " << resonance_hz << "\nq = " << q
            << "\nbrake = reverse\nresonance-tolerance-percent = 0\nq-tolerance-percent = 0\n";
    lra.section = section.str();
    lra.declaration.kind = actuator::Kind::lra;
    lra.declaration.rated_drive = rated_drive;
    lra.declaration.resonance_hz = resonance_hz;
    lra.declaration.q = q;
    lra.declaration.brake = actuator::Brake::reverse;
    lra.declaration.resonance_tolerance = 0.0;
    lra.declaration.q_tolerance = 0.0;
    return lra;
}

std::vector<render::Cue> planned(const std::string& score, const actuator::Declaration& declared,
                                 bool frequency,
                                 const std::map<std::string, std::string>& clefs = {}) {
    render::CueAdaptation adaptation;
    adaptation.frequency = frequency;
    adaptation.actuator = declared;
    adaptation.reverse = true;
    return expected_drives(score, adaptation, clefs);
}

std::string listing(const std::vector<LinesState>& states, std::size_t limit = 60) {
    std::ostringstream out;
    for (std::size_t i = 0; i < states.size() && i < limit; ++i) {
        out << "\n  " << states[i].seen.time_since_epoch().count() / 1000 << " us:";
        for (const int value : states[i].values) {
            out << " " << value;
        }
    }
    return out.str();
}

// The sampler has seen every line low again: it polls on a thread of its own, which under TCG can
// lag the lines themselves (reading them directly is not enough before taking its changes).
bool sampler_ends_low(const GpioLinesSampler& sampler) {
    const auto seen = sampler.changes();
    if (seen.empty()) {
        return false;
    }
    for (const int value : seen.back().values) {
        if (value != 0) {
            return false;
        }
    }
    return true;
}

// The first state seen at or after `from` in which line `index` has `value`.
std::optional<LinesState> first_state(const std::vector<LinesState>& states, std::size_t index,
                                      int value, Clock::time_point from = {}) {
    for (const auto& state : states) {
        if (state.seen >= from && state.values[index] == value) {
            return state;
        }
    }
    return std::nullopt;
}

// When that state was first seen.
std::optional<Clock::time_point> first_seen(const std::vector<LinesState>& states,
                                            std::size_t index, int value,
                                            Clock::time_point from = {}) {
    const auto state = first_state(states, index, value, from);
    return state ? std::optional(state->seen) : std::nullopt;
}

TEST(DaemonFeel, GpioErmOverdrivesTheNotesStartAndDrivesItsEndBackwards) {
    GpioSimChip sim({2});
    DaemonFixture daemon(driver_config("gpio-erm", "chip = " + sim.chip_name() +
                                                       "\nline = 0\ndirection-line = 1\n"
                                                       "carrier-hz = 100") +
                         slow_erm().section);
    GpioLinesSampler sampler(sim, {0, 1});  // motor, direction
    const auto score = whole_note();
    const auto drives = planned(score, slow_erm().declaration, false);
    ASSERT_EQ(drives.size(), 4u);
    EXPECT_EQ(drives[0].amplitude, 1.0);   // overdrive: the motor line steadily high
    EXPECT_EQ(drives[1].amplitude, 0.5);   // the rated drive: half of each 10 ms period
    EXPECT_EQ(drives[2].amplitude, -1.0);  // backwards: direction and motor line high
    EXPECT_EQ(drives[3].amplitude, 0.0);
    EXPECT_NEAR(drives[1].at - drives[0].at, 0.2 * std::log(2.0), 1e-6);
    EXPECT_NEAR(drives[3].at - drives[2].at, 0.2 * std::log(1.5), 1e-6);

    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    const double tolerance_s = played.onset_tolerance_s;
    ASSERT_TRUE(eventually([&] { return sim.value(0) == 0 && sim.value(1) == 0; }, 1s));
    ASSERT_TRUE(eventually([&] { return sampler_ends_low(sampler); }, 1s))
        << listing(sampler.changes(), 400);
    const auto states = sampler.changes();
    const auto start = first_seen(states, 0, 1);
    ASSERT_TRUE(start) << listing(states);
    // The overdrive: high without a break until the hold's first pulse ends, half a carrier
    // period after it began.
    const auto first_fall = first_seen(states, 0, 0, *start);
    ASSERT_TRUE(first_fall) << listing(states);
    EXPECT_NEAR(seconds_between(*start, *first_fall), drives[1].at - drives[0].at + 0.005,
                tolerance_s + 0.01)
        << listing(states);
    // Backwards at the note's end, for as long as the motor takes to stop, then every line low.
    const auto reversed = first_seen(states, 1, 1, *start);
    ASSERT_TRUE(reversed) << listing(states, 400);
    EXPECT_NEAR(seconds_between(*start, *reversed), drives[2].at - drives[0].at, tolerance_s + 0.01)
        << listing(states, 400);
    const auto stopped = first_seen(states, 1, 0, *reversed);
    ASSERT_TRUE(stopped) << listing(states, 400);
    EXPECT_NEAR(seconds_between(*reversed, *stopped), drives[3].at - drives[2].at,
                tolerance_s + 0.01)
        << listing(states, 400);
    for (const auto& state : states) {
        if (state.seen >= *reversed && state.seen < *stopped) {
            EXPECT_EQ(state.values[0], 1) << "braking at full scale" << listing(states, 400);
        }
    }
}

TEST(DaemonFeel, GpioLraBrakesInAntiPhaseWithItsBridgeSwapped) {
    GpioSimChip sim({2});
    // An LRA at 50 Hz with Q 10: its envelope's time constant is 64 ms, and braking at full
    // anti-phase stops it after 64 ms x ln 2 = 44 ms, two periods of 20 ms.
    const Declared lra = exact_lra(1.0, 50.0, 10.0);
    DaemonFixture daemon(
        driver_config("gpio-lra",
                      "chip = " + sim.chip_name() + "\nline-a = 0\nline-b = 1\nresonance-hz = 50") +
        lra.section);
    GpioLinesSampler sampler(sim, {0, 1});
    auto client = daemon.client();
    const std::string clef = testing::sine_clef(0.3, {50.0}, {0.5, 1.0});
    client->Compose("hil-feel", clef);
    const auto score =
        one_bar_score("hil-feel.clef.xml", "<Note length=\"half\" number=\"2\" string=\"1\"/>");
    const auto drives = planned(score, lra.declaration, true, {{"hil-feel.clef.xml", clef}});
    ASSERT_EQ(drives.size(), 3u);
    EXPECT_EQ(drives[0].amplitude, 1.0);
    EXPECT_EQ(drives[1].amplitude, -1.0);
    EXPECT_NEAR(drives[1].frequency_hz, 50.0, 0.01);  // at resonance it rings in phase
    const double brake_s = drives[2].at - drives[1].at;
    EXPECT_NEAR(brake_s, 10.0 / (std::numbers::pi * 50.0) * std::log(2.0), 1e-4);

    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    const double tolerance_s = played.onset_tolerance_s;
    ASSERT_TRUE(eventually([&] { return sim.value(0) == 0 && sim.value(1) == 0; }, 1s));
    ASSERT_TRUE(eventually([&] { return sampler_ends_low(sampler); }, 1s))
        << listing(sampler.changes(), 400);
    const auto states = sampler.changes();
    // At full strength the bridge alternates A and B without a gap, each high for half a period.
    // The anti-phase drive is the same half a period on, so at the switch (a period start) the
    // line that was high stays high for a whole period.
    struct Pulse {
        Clock::time_point rise, fall;
    };
    std::vector<Pulse> pulses;
    for (std::size_t line = 0; line < 2; ++line) {
        std::optional<Clock::time_point> rise;
        for (std::size_t i = 1; i < states.size(); ++i) {
            if (states[i].values[line] == 1 && states[i - 1].values[line] == 0) {
                rise = states[i].seen;
            } else if (states[i].values[line] == 0 && states[i - 1].values[line] == 1 && rise) {
                pulses.push_back({*rise, states[i].seen});
            }
        }
    }
    std::sort(pulses.begin(), pulses.end(),
              [](const Pulse& a, const Pulse& b) { return a.rise < b.rise; });
    ASSERT_GT(pulses.size(), 10u) << listing(states, 200);
    const double period_s = 0.02;
    // (A wake-up of the PWM thread late under TCG also stretches a pulse now and then: look
    // only from just before the note's end.)
    const auto note_end = pulses.front().rise +
                          std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                              drives[1].at - drives[0].at - period_s));
    const auto whole = std::find_if(pulses.begin(), pulses.end(), [&](const Pulse& p) {
        return p.rise >= note_end && seconds_between(p.rise, p.fall) > 0.75 * period_s;
    });
    ASSERT_NE(whole, pulses.end()) << "no anti-phase" << listing(states, 200);
    const auto switched = whole->rise + std::chrono::milliseconds(10);
    // The swap waits for the next period start: within one period of the note's end.
    const double switch_at = seconds_between(pulses.front().rise, switched);
    EXPECT_GE(switch_at, drives[1].at - drives[0].at - tolerance_s) << listing(states, 200);
    EXPECT_LE(switch_at, drives[1].at - drives[0].at + period_s + tolerance_s)
        << listing(states, 200);
    // Anti-phase for the brake's time (the stop comes at the next edge), then every line low.
    const auto last_fall =
        std::max_element(pulses.begin(), pulses.end(), [](const Pulse& a, const Pulse& b) {
            return a.fall < b.fall;
        })->fall;
    EXPECT_NEAR(seconds_between(switched, last_fall), brake_s, period_s / 2 + tolerance_s)
        << listing(states, 200);
}

TEST(DaemonFeel, SysfsPwmOverdrivesThenReversesWithItsDirectionLine) {
    PwmSimChip pwm;
    GpioSimChip sim({1});
    const unsigned channel = 0;
    const auto chip = pwm.sysfs_dir().filename().string().substr(std::string("pwmchip").size());
    DaemonFixture daemon(driver_config("sysfs-pwm", "chip = " + chip +
                                                        "\nchannel = 0\nmode = erm\n"
                                                        "direction-chip = " +
                                                        sim.chip_name() + "\ndirection-line = 0") +
                         slow_erm().section);
    GpioLinesSampler direction(sim, {0});
    pwm.clear_log();
    const auto score = whole_note();
    const auto drives = planned(score, slow_erm().declaration, false);
    ASSERT_EQ(drives.size(), 4u);
    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    const double tolerance_s = played.onset_tolerance_s;
    ASSERT_TRUE(eventually([&] { return sim.value(0) == 0; }, 1s));
    ASSERT_TRUE(eventually([&] { return sampler_ends_low(direction); }, 1s));

    // The channel: full duty (overdrive), half (rated), 0 while the direction turns, full again
    // (backwards), then 0.
    std::vector<PwmApplied> applied;
    std::ostringstream log;
    for (const auto& entry : pwm.log()) {
        if (entry.channel == channel) {
            applied.push_back(entry);
            log << "\n  " << entry;
        }
    }
    std::vector<std::pair<Clock::time_point, std::uint64_t>> duties;
    for (const auto& entry : applied) {
        if (duties.empty() || duties.back().second != entry.duty_cycle_ns) {
            duties.emplace_back(entry.time, entry.duty_cycle_ns);
        }
    }
    ASSERT_GE(duties.size(), 5u) << log.str();
    EXPECT_EQ(duties[0].second, 50000u) << log.str();
    EXPECT_EQ(duties[1].second, 25000u) << log.str();
    EXPECT_EQ(duties[2].second, 0u) << log.str();
    EXPECT_EQ(duties[3].second, 50000u) << log.str();
    EXPECT_EQ(duties[4].second, 0u) << log.str();
    EXPECT_NEAR(seconds_between(duties[0].first, duties[1].first), drives[1].at - drives[0].at,
                tolerance_s)
        << log.str();
    EXPECT_NEAR(seconds_between(duties[0].first, duties[3].first), drives[2].at - drives[0].at,
                tolerance_s)
        << log.str();
    EXPECT_NEAR(seconds_between(duties[3].first, duties[4].first), drives[3].at - drives[2].at,
                tolerance_s)
        << log.str();
    // The direction line is high exactly while the channel drives backwards.
    const auto states = direction.changes();
    const auto up = first_state(states, 0, 1);
    ASSERT_TRUE(up) << listing(states);
    // The sampler's own thread can be late to see it: the line rose between its sample before
    // and the one that saw it, and before the channel drove backwards.
    EXPECT_LE(seconds_between(duties[0].first, up->before),
              drives[2].at - drives[0].at + tolerance_s)
        << listing(states);
    EXPECT_GE(seconds_between(duties[0].first, up->seen), drives[2].at - drives[0].at - tolerance_s)
        << listing(states);
    EXPECT_LT(up->before, duties[3].first) << listing(states);
}

TEST(DaemonFeel, EvdevOverdrivesWithFullMagnitudeAndBrakesWithANegativeOne) {
    UinputVibrator vibrator;  // records every effect the kernel hands it
    // An LRA at 200 Hz (a 5 ms period, exact in the kernel's milliseconds) with Q 40: 64 ms
    // envelope; rated at half of full scale, so the overdrive lasts 64 ms x ln 2 = 44 ms and the
    // brake 64 ms x ln 1.5 = 26 ms.
    const Declared lra = exact_lra(0.5, 200.0, 40.0);
    DaemonFixture daemon(driver_config("evdev", "device = " + vibrator.event_node().string() +
                                                    "\nanti-phase = true") +
                         lra.section);
    const auto score = whole_note("4");  // 200 Hz
    const auto drives = planned(score, lra.declaration, true);
    ASSERT_EQ(drives.size(), 4u);
    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    const double tolerance_s = played.onset_tolerance_s;
    vibscore::testing::wait_until([&] { return vibrator.playing().empty(); }, 5s, 2ms);
    // Each start the device saw, with the magnitude of the effect it started.
    std::map<int, ff_effect> uploaded;
    std::vector<std::pair<Clock::time_point, int>> starts;
    std::ostringstream seen;
    for (const auto& event : vibrator.timeline()) {
        seen << "\n  " << event;
        if (event.kind == FfEvent::Kind::Upload && event.value == 0) {
            uploaded[event.effect_id] = event.effect;
        } else if (event.kind == FfEvent::Kind::Play && event.value != 0) {
            starts.emplace_back(event.time, uploaded[event.effect_id].u.periodic.magnitude);
        }
    }
    ASSERT_EQ(starts.size(), 3u) << seen.str();
    EXPECT_EQ(starts[0].second, 0x7fff) << "overdrive at full magnitude";
    EXPECT_EQ(starts[1].second, 16384) << "the rated drive";
    EXPECT_EQ(starts[2].second, -0x7fff) << "anti-phase: a negative magnitude";
    EXPECT_NEAR(seconds_between(starts[0].first, starts[1].first), drives[1].at - drives[0].at,
                tolerance_s)
        << seen.str();
    EXPECT_NEAR(seconds_between(starts[0].first, starts[2].first), drives[2].at - drives[0].at,
                tolerance_s)
        << seen.str();
    EXPECT_TRUE(vibrator.playing().empty()) << "stopped once the brake is done" << seen.str();
}

}  // namespace
}  // namespace vibscore::hil
