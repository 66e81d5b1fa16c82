// vibscored killed with SIGKILL mid-note, per backend, in the guest: the actuator ends off with
// no daemon left to switch it off (the kernel does it), and `vibscored --safe-off` (the unit's
// ExecStopPost=) leaves it off too. docs/drivers/gpio.md and docs/drivers/sysfs.md say why.
#include <gtest/gtest.h>

#include <optional>
#include <sstream>
#include <thread>

#include "tests/hil/gpio_sim_chip.hpp"
#include "tests/hil/kernel_files.hpp"
#include "tests/hil/score_expectations.hpp"
#include "tests/hil/uinput_vibrator.hpp"
#include "tests/hil/uleds_led.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/pace.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;
using testing::DaemonFixture;
using Clock = std::chrono::steady_clock;

// One whole note at full strength: 0.8 s steadily on (quarter = 0.2 s on this clef).
const std::string kLongNote =
    one_bar_score("lra-phone.clef.xml", "<Note length=\"whole\" number=\"9\" string=\"1\"/>");
constexpr double kNote_s = 0.8;

void safe_off(const DaemonFixture& daemon) {
    const auto result = testing::run_command(
        {testing::required_env("VIBSCORED"), "--config", daemon.config().string(), "--safe-off"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
}

TEST(DaemonSigkill, GpioLineHighAtTheKillFallsLowThroughThePullDownBias) {
    GpioSimChip sim({1});
    // The board pulls the line up: released without a bias of its own, it would read high.
    sim.set_pull(0, true);
    ASSERT_EQ(sim.value(0), 1);
    DaemonFixture daemon(
        driver_config("gpio-erm", "chip = " + sim.chip_name() + "\nline = 0\ncarrier-hz = 100"));
    EXPECT_EQ(sim.value(0), 0) << "requested low";
    auto client = daemon.client();
    client->Play(kLongNote, {});
    // Full strength holds the motor line high with no edges.
    ASSERT_TRUE(eventually([&] { return sim.value(0) == 1; }, 5s)) << daemon.daemon_log();
    const auto on = Clock::now();
    daemon.kill_daemon();
    const double killed_after_s = seconds_between(on, Clock::now());
    ASSERT_LT(killed_after_s, kNote_s) << "the kill came after the note's end";
    // The kernel released the line with the process's fds: no wait, no daemon.
    EXPECT_EQ(sim.value(0), 0) << "killed " << killed_after_s << " s into the note";

    safe_off(daemon);
    EXPECT_EQ(sim.value(0), 0);
}

TEST(DaemonSigkill, LedGoesOffWhenTheTransientTimerArmedWithTheNotesRemainingTimeExpires) {
    UledsLed led("vibrator");
    // duration-ms far beyond the note: a timer armed with it instead of the note's remaining
    // time would keep the LED on for 10 s after the kill.
    DaemonFixture daemon(
        driver_config("led-vibrator", "sysfs-root = /sys\nled = vibrator\nduration-ms = 10000"));
    led.clear_changes();
    auto client = daemon.client();
    client->Play(kLongNote, {});
    ASSERT_TRUE(led.wait_for([](const BrightnessChange& c) { return c.brightness > 0; }, 5s))
        << daemon.daemon_log();
    // Killed 200 ms into the 1 s note: where in the note the kill falls is what is tested (the
    // kernel's timer must hold the note's remaining time), so this is paced, not waited.
    vibscore::testing::pace_for(200ms);
    daemon.kill_daemon();
    const auto killed = Clock::now();

    ASSERT_TRUE(led.wait_for([](const BrightnessChange& c) { return c.brightness == 0; }, 5s))
        << "still on 5 s after the kill";
    std::optional<Clock::time_point> on, off;
    std::ostringstream listing;
    for (const auto& change : led.changes()) {
        listing << "\n  " << change.time.time_since_epoch().count() / 1000
                << " us: " << change.brightness;
        if (change.brightness > 0 && !on) {
            on = change.time;
        } else if (change.brightness == 0 && on && !off) {
            off = change.time;
        }
    }
    ASSERT_TRUE(on && off) << listing.str();
    EXPECT_GT(*off, killed) << "on until the kernel's timer, not switched off" << listing.str();
    // Off at the note's end (the guest's timers under TCG can be tens of ms late).
    EXPECT_NEAR(seconds_between(*on, *off), kNote_s, 0.15) << listing.str();

    safe_off(daemon);
    EXPECT_EQ(led.changes().back().brightness, 0) << listing.str();
    EXPECT_EQ(std::stoi(read_attribute(led.sysfs_dir() / "brightness")), 0);
}

TEST(DaemonSigkill, EvdevEffectsStopAndAreErasedWhenTheKilledDaemonsFdCloses) {
    UinputVibrator vibrator;
    DaemonFixture daemon(driver_config("evdev", "device = " + vibrator.event_node().string()));
    auto client = daemon.client();
    client->Play(kLongNote, {});
    ASSERT_TRUE(vibrator.wait_for([](const FfEvent& e) {
        return e.kind == FfEvent::Kind::Play && e.value != 0;
    })) << daemon.daemon_log();
    ASSERT_FALSE(vibrator.playing().empty());
    const auto on = Clock::now();
    daemon.kill_daemon();
    ASSERT_LT(seconds_between(on, Clock::now()), kNote_s) << "the kill came after the note's end";

    // The kernel stops and erases every effect the closed fd owned (evdev's flush).
    EXPECT_TRUE(eventually([&] { return vibrator.playing().empty(); }, 2s));
    EXPECT_TRUE(eventually([&] { return vibrator.effects().empty(); }, 2s));

    safe_off(daemon);
    EXPECT_TRUE(vibrator.playing().empty());
    EXPECT_TRUE(vibrator.effects().empty());
}

}  // namespace
}  // namespace vibscore::hil
