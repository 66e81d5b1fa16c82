// Switching the actuator backend of the running daemon over D-Bus: to the example driver
// module, with playback in progress, and to a backend that fails to open.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;

constexpr uid_t kNobody = 65534;

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
}

class DriverSwitch : public ::testing::Test {
  protected:
    testing::TempDir dir;
    std::filesystem::path module_trace = dir.path() / "trace-driver.log";
    DaemonFixture daemon{"drivers-dir = " + testing::required_env("VIBSCORE_EXAMPLE_DRIVERS") +
                         "\n[trace]\npath = " + module_trace.string() + "\n" + "[broken]\n"};

    std::string property(const std::string& name) const {
        return daemon
            .busctl({"get-property", "org.vibscore.Haptics1", "/org/vibscore/Haptics1",
                     "org.vibscore.Haptics1", name})
            .out;
    }
};

TEST_F(DriverSwitch, ListsBuiltInDriversAndModules) {
    const auto listed = daemon.call({"ListDrivers"});
    ASSERT_EQ(listed.exit_code, 0) << listed.err;
    EXPECT_THAT(listed.out, HasSubstr("\"sim\""));
    EXPECT_THAT(listed.out, HasSubstr("\"trace\" \"example driver module"));
}

TEST_F(DriverSwitch, APlaybackEndsAndTheNewDriverPlaysTheNextOne) {
    auto client = daemon.client();
    const auto ringing = client->Play(
        "ringtone", std::map<std::string, sdbus::Variant>{{"repeat", sdbus::Variant(-1)}});
    const auto switched = daemon.call({"SwitchDriver", "s", "trace"});
    ASSERT_EQ(switched.exit_code, 0) << switched.err << daemon.daemon_log();
    std::string reason;
    ASSERT_TRUE(client->wait_finished(ringing, &reason));
    EXPECT_EQ(reason, "driver-switch");
    EXPECT_EQ(property("Driver"), "s \"trace\"\n");
    EXPECT_EQ(property("Capabilities"), "as 2 \"amplitude-control\" \"frequency-control\"\n");
    // The old actuator was switched off when the playback ended.
    const auto rows = daemon.trace_rows();
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows.back().amplitude, 0.0);

    const auto id = client->Play("touch-click", {});
    ASSERT_TRUE(client->wait_finished(id, &reason));
    EXPECT_EQ(reason, "completed");
    const std::string commands = read_text(module_trace);
    EXPECT_THAT(commands, HasSubstr(" open\n"));
    EXPECT_THAT(commands, HasSubstr(" apply "));
    EXPECT_THAT(commands, HasSubstr(" off\n"));
    EXPECT_THAT(daemon.daemon_log(), HasSubstr("driver is now trace"));
}

TEST_F(DriverSwitch, OnlyPrivilegedCallersSwitchAndOnlyToKnownDrivers) {
    const auto denied = daemon.call({"SwitchDriver", "s", "trace"}, kNobody);
    EXPECT_THAT(denied.err,
                HasSubstr("Switching the driver needs org.vibscore.manage; polkit is not running, "
                          "so only root and group vibscore have it, and uid 65534 is neither"));
    const auto unknown = daemon.call({"SwitchDriver", "s", "piezo"});
    EXPECT_THAT(unknown.err, HasSubstr("no driver \"piezo\" (available: sim, evdev, gpio-erm, "
                                       "gpio-lra, sysfs-pwm, led-vibrator, timed-output, trace)"));
    EXPECT_EQ(property("Driver"), "s \"sim\"\n");
}

TEST_F(DriverSwitch, ADriverThatFailsToOpenLeavesThePreviousOneRunning) {
    daemon.write_config("drivers-dir = " + testing::required_env("VIBSCORE_EXAMPLE_DRIVERS") +
                            "\n[trace]\npath = /nonexistent/dir/log\n",
                        "trace = " + daemon.trace().string());
    daemon.signal_daemon(SIGHUP);
    testing::wait_until(
        [&] { return daemon.daemon_log().find("configuration reloaded") != std::string::npos; });
    const auto failed = daemon.call({"SwitchDriver", "s", "trace"});
    EXPECT_NE(failed.exit_code, 0);
    EXPECT_THAT(failed.err, HasSubstr("cannot open /nonexistent/dir/log"));
    EXPECT_EQ(property("Driver"), "s \"sim\"\n");
    auto client = daemon.client();
    const auto rows_before = daemon.trace_rows().size();
    const auto id = client->Play("touch-click", {});
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason));
    EXPECT_EQ(reason, "completed");
    EXPECT_GT(daemon.trace_rows().size(), rows_before);  // the sim, reopened, still plays
}

TEST_F(DriverSwitch, TheClientListsAndSwitchesDrivers) {
    const auto vibscore = testing::required_env("VIBSCORE");
    const auto listed = testing::run_command({vibscore, "drivers"});
    ASSERT_EQ(listed.exit_code, 0) << listed.err;
    EXPECT_THAT(listed.out, HasSubstr("* sim\t"));
    EXPECT_THAT(listed.out, HasSubstr("  trace\texample driver module"));
    const auto switched = testing::run_command({vibscore, "driver", "trace"});
    EXPECT_EQ(switched.exit_code, 0) << switched.err;
    EXPECT_EQ(switched.out,
              "driver trace: amplitude-control frequency-control\nswitched at run time "
              "(SwitchDriver, vibscore driver trace); a reload or a restart returns to the "
              "configuration's driver = sim\n"
              "actuator: none declared: strengths play as written ([actuator] in vibscored.conf, "
              "docs/drivers.md)\n");
    const auto unknown = testing::run_command({vibscore, "driver", "piezo"});
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_EQ(unknown.err,
              "vibscore: not found: no driver \"piezo\" (available: sim, evdev, gpio-erm, "
              "gpio-lra, sysfs-pwm, led-vibrator, timed-output, trace)\n");
}

TEST_F(DriverSwitch, TheClientSaysWhyTheDriverRunsAndWhenItIsAlreadyInUse) {
    const auto vibscore = testing::required_env("VIBSCORE");
    const auto shown = testing::run_command({vibscore, "driver"});
    EXPECT_EQ(shown.exit_code, 0) << shown.err;
    // The reason names the line of the file that says so.
    const std::string configured = "configured at " + daemon.config().string() + ":2: driver = sim";
    const std::string undeclared =
        "sim: simulates the model its [sim] section sets (model, resonance-hz, q, spin-up-ms, "
        "spin-down-ms in vibscored.conf), no actuator being declared\n"
        "actuator: none declared: strengths play as written ([actuator] in vibscored.conf, "
        "docs/drivers.md)\n";
    EXPECT_EQ(shown.out,
              "driver sim: amplitude-control frequency-control\n" + configured + "\n" + undeclared);
    EXPECT_EQ(property("DriverReason"), "s \"" + configured + "\"\n");
    // Switching to the driver in use would only end what plays and reopen it: it says so.
    auto client = daemon.client();
    const auto ringing = client->Play(
        "ringtone", std::map<std::string, sdbus::Variant>{{"repeat", sdbus::Variant(-1)}});
    const auto same = testing::run_command({vibscore, "driver", "sim"});
    EXPECT_EQ(same.exit_code, 0) << same.err;
    EXPECT_EQ(same.out,
              "driver sim is already in use; nothing changed\ndriver sim: amplitude-control "
              "frequency-control\n" +
                  configured + "\n" + undeclared);
    std::string reason;
    EXPECT_FALSE(client->wait_finished(ringing, &reason, std::chrono::milliseconds(300))) << reason;
    EXPECT_THAT(daemon.daemon_log(), ::testing::Not(HasSubstr("driver is now")));
}

TEST_F(DriverSwitch, DriverAutoWithNoDeviceRunsSimAndWarnsWhatItSearched) {
    testing::TempDir input;
    daemon.write_config("driver = auto\n[evdev]\ninput-dir = " + input.path().string(),
                        "trace = " + daemon.trace().string());
    daemon.signal_daemon(SIGHUP);
    testing::wait_until(
        [&] { return daemon.daemon_log().find("configuration reloaded") != std::string::npos; });
    EXPECT_EQ(property("Driver"), "s \"sim\"\n");
    EXPECT_THAT(property("DriverReason"),
                HasSubstr("vibscored.conf:4) found no actuator, so driver sim plays (nothing "
                          "vibrates). Searched: evdev: no force-feedback device in " +
                          input.path().string()));
    // A warning in the log (journald files <4> as priority warning).
    EXPECT_THAT(daemon.daemon_log(), HasSubstr("<4>driver = auto (" + daemon.config().string() +
                                               ":4) found no actuator"));
}

}  // namespace
}  // namespace vibscore
