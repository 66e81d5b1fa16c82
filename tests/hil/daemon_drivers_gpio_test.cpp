// vibscored with driver = gpio-erm and gpio-lra in the guest, on gpio-sim lines: the software
// PWM as the GPIO character device carries it out (duty cycles, the enable line, an H-bridge's
// antiphase), note timing, lines low afterwards, and the maximum on-time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "tests/hil/gpio_lines_sampler.hpp"
#include "tests/hil/gpio_sim_chip.hpp"
#include "tests/hil/score_expectations.hpp"
#include "tests/hil/watched_playback.hpp"
#include "tests/support/daemon_fixture.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;
using testing::DaemonFixture;
using Clock = std::chrono::steady_clock;

const std::string kPhoneClef = "lra-phone.clef.xml";  // quarter = 0.2 s; string 1 = 155 Hz

std::string listing(const std::vector<LinesState>& states, std::size_t limit = 40) {
    std::ostringstream out;
    for (std::size_t i = 0; i < states.size() && i < limit; ++i) {
        out << "\n  " << states[i].seen.time_since_epoch().count() / 1000 << " us:";
        for (const int value : states[i].values) {
            out << " " << value;
        }
    }
    if (states.size() > limit) {
        out << "\n  ... " << states.size() - limit << " more";
    }
    return out.str();
}

// Where line `index` was high: [first rise, last fall) by the sampler's `seen` times.
struct Driven {
    Clock::time_point first_rise, last_fall;
    std::size_t rises = 0;
};

Driven driven(const std::vector<LinesState>& states, std::size_t index) {
    Driven result;
    for (std::size_t i = 0; i < states.size(); ++i) {
        const bool high = states[i].values[index] == 1;
        const bool was_high = i > 0 && states[i - 1].values[index] == 1;
        if (high && !was_high) {
            result.first_rise = result.rises == 0 ? states[i].seen : result.first_rise;
            ++result.rises;
        } else if (!high && was_high) {
            result.last_fall = states[i].seen;
        }
    }
    return result;
}

// Waits until the sampler has seen every line low (the PWM thread stops at its next edge).
bool settles_low(const GpioLinesSampler& sampler) {
    return eventually(
        [&] {
            const auto last = sampler.changes().back().values;
            return std::all_of(last.begin(), last.end(), [](int value) { return value == 0; });
        },
        1s);
}

// The duty cycle of each whole period of line `index` within [begin, end), rise to rise, that
// lasted its nominal length (within 25 %). Under TCG on a busy host a wake-up of the PWM thread
// can be milliseconds late, which stretches or squashes the pulses around it; those periods
// are left out, and the median of the rest is the waveform the backend asked for.
std::vector<double> clean_period_duties(const std::vector<LinesState>& states, std::size_t index,
                                        double period_s, Clock::time_point begin,
                                        Clock::time_point end) {
    std::vector<double> duties;
    std::optional<Clock::time_point> rise, fall;
    for (std::size_t i = 1; i < states.size(); ++i) {
        if (states[i].seen < begin || states[i].seen >= end) {
            continue;
        }
        const int value = states[i].values[index];
        if (value == states[i - 1].values[index]) {
            continue;
        }
        if (value == 0) {
            fall = states[i].seen;
            continue;
        }
        if (rise && fall && *fall > *rise) {
            const double length = seconds_between(*rise, states[i].seen);
            if (std::abs(length - period_s) <= 0.25 * period_s) {
                duties.push_back(seconds_between(*rise, *fall) / length);
            }
        }
        rise = states[i].seen;
    }
    return duties;
}

// The share of [begin, end) in which some line was high, by the `seen` times of the states.
double fraction_either_high(const std::vector<LinesState>& states, Clock::time_point begin,
                            Clock::time_point end) {
    Clock::duration high{0};
    for (std::size_t i = 0; i < states.size(); ++i) {
        const auto& values = states[i].values;
        if (std::none_of(values.begin(), values.end(), [](int value) { return value == 1; })) {
            continue;
        }
        const auto from = std::max(states[i].seen, begin);
        const auto to = std::min(i + 1 < states.size() ? states[i + 1].seen : end, end);
        if (to > from) {
            high += to - from;
        }
    }
    return std::chrono::duration<double>(high).count() / seconds_between(begin, end);
}

TEST(DaemonGpio, ErmDrivesItsLineAtTheNotesStrengthAsDutyCycleWithTheEnableLine) {
    GpioSimChip sim({2});
    // A 10 ms carrier period: under TCG on a busy host a wake-up can be milliseconds late.
    DaemonFixture daemon(driver_config("gpio-erm", "chip = " + sim.chip_name() +
                                                       "\nline = 0\nenable-line = 1\n"
                                                       "carrier-hz = 100"));
    // Started after the daemon: on the guest's one vCPU it competes with everything else.
    GpioLinesSampler sampler(sim, {0, 1});  // motor, enable
    // Strength 0.5 for 0.8 s.
    const auto score =
        one_bar_score(kPhoneClef, "<Note length=\"whole\" number=\"4\" string=\"1\"/>");
    render::CueAdaptation adaptation;
    adaptation.frequency = false;
    const auto drives = expected_drives(score, adaptation);
    ASSERT_EQ(drives.size(), 2u);
    ASSERT_EQ(drives[0].amplitude, 0.5);
    const double note_s = drives[1].at - drives[0].at;

    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    ASSERT_TRUE(settles_low(sampler)) << listing(sampler.changes());
    EXPECT_EQ(sim.value(0), 0);
    EXPECT_EQ(sim.value(1), 0);

    const auto states = sampler.changes();
    const auto motor = driven(states, 0);
    const auto enable = driven(states, 1);
    ASSERT_GT(motor.rises, 0u) << listing(states);
    // The note starts with the Play call (bench/evdev_latency measures such latencies). The
    // call, the parse and the render before the first edge take the guest's one vCPU for many
    // timeslices, and a guest on a busy host stalls in any of them: the bound grows by every
    // stall between the call and the edge, not only by the longest.
    const double stalled = played.stalled_s(played.asked, motor.first_rise);
    EXPECT_LT(seconds_between(played.asked, motor.first_rise), 0.25 + kOnsetTolerance_s + stalled)
        << "the Play call to the first edge; the guest was stopped for " << stalled * 1000
        << " ms of it, in " << played.stalls.size() << " stalls while the score played";
    // On for the note, within a carrier period and the onset tolerance.
    EXPECT_NEAR(seconds_between(motor.first_rise, motor.last_fall), note_s,
                played.onset_tolerance_s + 0.01);
    // The carrier's periods at the note's strength as duty cycle.
    const double periods = note_s * 100;
    const auto duties = clean_period_duties(states, 0, 0.01, motor.first_rise, motor.last_fall);
    ASSERT_GE(duties.size(), 10u) << listing(states, 200);
    EXPECT_NEAR(median(duties), 0.5, 0.1) << listing(states, 200);
    EXPECT_LE(static_cast<double>(motor.rises), periods + 1) << listing(states, 200);

    // The enable line is high throughout the note, and the motor line never without it.
    EXPECT_EQ(enable.rises, 1u) << listing(states);
    EXPECT_LE(enable.first_rise, motor.first_rise);
    EXPECT_GE(enable.last_fall, motor.last_fall);
    for (const auto& state : states) {
        EXPECT_FALSE(state.values[0] == 1 && state.values[1] == 0)
            << "motor high without enable at " << state.seen.time_since_epoch().count();
    }
}

TEST(DaemonGpio, LraDrivesTwoLinesInAntiphaseAtTheNotesFrequencyNeverBothHigh) {
    GpioSimChip sim({2});
    // The resonance is far from the notes' 50 Hz: a backend that ignored the note's frequency
    // would show more than twice the pulses.
    DaemonFixture daemon(driver_config(
        "gpio-lra", "chip = " + sim.chip_name() + "\nline-a = 0\nline-b = 1\nresonance-hz = 120"));
    GpioLinesSampler sampler(sim, {0, 1});  // the H-bridge's inputs A and B
    auto client = daemon.client();
    // A clef of the test's own, composed into the daemon's store: 50 Hz, whose 20 ms period is
    // long against the guest's late wake-ups on a busy host (the shipped LRA clef starts at
    // 155 Hz), at full and at half strength, a half note lasting 0.6 s.
    const std::string clef = testing::sine_clef(0.3, {50.0}, {0.5, 1.0});
    client->Compose("hil-lra", clef);
    // Full strength for 0.6 s, a rest of 0.3 s, half strength for 0.6 s.
    const auto score = one_bar_score("hil-lra.clef.xml",
                                     "<Note length=\"half\" number=\"2\" string=\"1\"/>"
                                     "<Rest length=\"quarter\"/>"
                                     "<Note length=\"half\" number=\"1\" string=\"1\"/>");
    const auto drives = expected_drives(score, {}, {{"hil-lra.clef.xml", clef}});
    ASSERT_EQ(drives.size(), 4u);
    ASSERT_EQ(drives[0].frequency_hz, 50.0);
    ASSERT_EQ(drives[0].amplitude, 1.0);

    const auto id = client->Play(score, {});
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason)) << daemon.daemon_log();
    EXPECT_EQ(reason, "completed");
    ASSERT_TRUE(settles_low(sampler)) << listing(sampler.changes());

    const auto states = sampler.changes();
    // The bridge never shorts its supply.
    for (const auto& state : states) {
        ASSERT_FALSE(state.values[0] == 1 && state.values[1] == 1)
            << "A and B both high at " << state.seen.time_since_epoch().count() << " ("
            << sampler.torn_samples() << " torn samples left out)" << listing(states);
    }
    // Antiphase: the lines take turns, A, B, A, B. A wake-up of the PWM thread later than a
    // pulse lasts squashes that pulse, which shows as one line twice in a row: on a host whose
    // cores are busy with other work, the guest stalls often enough for up to one in ten.
    std::vector<std::size_t> turns;
    for (std::size_t i = 1; i < states.size(); ++i) {
        for (std::size_t line = 0; line < 2; ++line) {
            if (states[i].values[line] == 1 && states[i - 1].values[line] == 0) {
                turns.push_back(line);
            }
        }
    }
    std::size_t repeats = 0;
    for (std::size_t i = 1; i < turns.size(); ++i) {
        repeats += turns[i] == turns[i - 1] ? 1 : 0;
    }
    EXPECT_GE(turns.size(), 60u) << listing(states, 200);
    EXPECT_LE(repeats, turns.size() / 5) << turns.size() << " turns" << listing(states, 200);

    const auto start = driven(states, 0).first_rise;
    const auto at = [&](double seconds) {
        return start + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(seconds - drives[0].at));
    };
    // Inside each note (20 ms in from its edges): how much of the time one line or the other
    // is high (at full strength the square wave has no gap; at half strength each line is high
    // for a sixth of the period, (2/pi) asin(0.5) = 1/3 of its half, so that the pulses'
    // fundamental is half), and at most one pulse per line in each period of the note's
    // frequency (late wake-ups only take pulses away).
    struct Note {
        double from_s, to_s, driven_share;
    };
    for (const Note note :
         {Note{drives[0].at, drives[1].at, 1.0}, Note{drives[2].at, drives[3].at, 1.0 / 3.0}}) {
        SCOPED_TRACE("note at " + std::to_string(note.from_s) + " s");
        const auto begin = at(note.from_s + 0.02);
        const auto end = at(note.to_s - 0.02);
        EXPECT_NEAR(fraction_either_high(states, begin, end), note.driven_share, 0.12)
            << listing(states, 200);
        const double periods = (note.to_s - note.from_s - 0.04) * drives[0].frequency_hz;
        for (std::size_t line = 0; line < 2; ++line) {
            std::size_t rises = 0;
            for (std::size_t i = 1; i < states.size(); ++i) {
                rises += states[i].seen >= begin && states[i].seen < end &&
                                 states[i].values[line] == 1 && states[i - 1].values[line] == 0
                             ? 1
                             : 0;
            }
            // A window `periods` long holds at most floor(periods) + 1 rises, however it lies
            // against the pulses; the tolerance keeps 27.9999... periods from counting as 27.
            EXPECT_LE(static_cast<double>(rises), std::floor(periods + 1e-6) + 1)
                << "line " << line;
            EXPECT_GE(static_cast<double>(rises), 0.5 * periods) << "line " << line;
        }
    }
}

TEST(DaemonGpio, TheMaximumOnTimeCutsALongNoteShort) {
    GpioSimChip sim({1});
    DaemonFixture daemon(driver_config(
        "gpio-erm", "chip = " + sim.chip_name() + "\nline = 0\nmax-on-time-ms = 200"));
    GpioLinesSampler sampler(sim, {0});
    // Full strength for 1 s: two tied notes make one drive.
    const auto score =
        one_bar_score(kPhoneClef,
                      "<Note length=\"whole\" number=\"9\" string=\"1\" legato=\"1\"/>"
                      "<Note length=\"quarter\" number=\"9\" string=\"1\" legato=\"1\"/>");
    render::CueAdaptation adaptation;
    adaptation.frequency = false;
    const auto drives = expected_drives(score, adaptation);
    ASSERT_EQ(drives.size(), 2u);
    ASSERT_EQ(drives[0].amplitude, 1.0);
    ASSERT_DOUBLE_EQ(drives[1].at, 1.0);

    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    const auto states = sampler.changes();
    const auto motor = driven(states, 0);
    EXPECT_EQ(motor.rises, 1u) << listing(states);
    EXPECT_NEAR(seconds_between(motor.first_rise, motor.last_fall), 0.2, played.onset_tolerance_s)
        << listing(states);
    EXPECT_EQ(sim.value(0), 0);
    EXPECT_NE(daemon.daemon_log().find("maximum on-time"), std::string::npos)
        << daemon.daemon_log();
}

}  // namespace
}  // namespace vibscore::hil
