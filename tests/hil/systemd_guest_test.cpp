// The packages as a device runs them: inside the systemd guest (vm-run --root-image), after
// `apt install ./vibscored_*.deb ./vibscore_*.deb`, vibscored started by systemd and D-Bus
// activation on the real system bus, as user vibscore, with polkit and the shipped udev rules.
// The tests run in this order (gtest keeps a file's order): the last one removes the packages.
#include <gtest/gtest.h>

#include <grp.h>
#include <pwd.h>
#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include "tests/hil/gpio_sim_chip.hpp"
#include "tests/hil/uinput_vibrator.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {
namespace {

using vibscore::testing::CommandResult;
using vibscore::testing::run_command;

const std::string kConfig = "/etc/vibscore/vibscored.conf";
const std::string kBusctlObject =
    "busctl call org.vibscore.Haptics1 /org/vibscore/Haptics1 org.vibscore.Haptics1 ";
const char* const kScore =
    "<VibScore><Title>a click</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"l\"><Note length=\"16th\" number=\"9\" string=\"6\"/></Bar></VibScore>";

CommandResult sh(const std::string& command) {
    return run_command({"/bin/sh", "-c", command});
}

// As the user alice, in no group and in no session.
CommandResult as_alice(const std::string& command) {
    return run_command({"/usr/sbin/runuser", "-u", "alice", "--", "/bin/sh", "-c", command});
}

std::string out_of(const std::string& command) {
    const auto result = sh(command);
    EXPECT_EQ(result.exit_code, 0) << command << ": " << result.err;
    return result.out;
}

bool eventually(const std::function<bool()>& condition,
                std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    return vibscore::testing::wait_until(condition, timeout, std::chrono::milliseconds(50));
}

std::string main_pid() {
    auto pid = out_of("systemctl show --property=MainPID --value vibscored");
    return pid.substr(0, pid.find('\n'));
}

// Writes vibscored.conf (the shipped clefs, the store, and `body`) and restarts the daemon.
void configure(const std::string& body) {
    std::ofstream(kConfig) << "[daemon]\nstore = /var/lib/vibscore\n" << body << "\n";
    // The tests restart it more often than the unit's start limit allows.
    const auto restarted = sh("systemctl reset-failed vibscored; systemctl restart vibscored");
    ASSERT_EQ(restarted.exit_code, 0)
        << restarted.err << out_of("journalctl -u vibscored -b -o cat --no-pager | tail -20");
}

gid_t vibscore_gid() {
    const group* found = getgrnam("vibscore");
    return found == nullptr ? static_cast<gid_t>(-1) : found->gr_gid;
}

// The node belongs to group vibscore, read-write for it and nobody else.
void expect_vibscore_device(const std::string& node) {
    struct stat status {};
    ASSERT_EQ(stat(node.c_str(), &status), 0) << node;
    EXPECT_EQ(status.st_gid, vibscore_gid()) << node;
    EXPECT_EQ(status.st_mode & 0777, 0660u) << node;
}

TEST(SystemdGuest, ThePackagesCreatedUserVibscoreAndEnabledTheUnit) {
    const passwd* user = getpwnam("vibscore");
    ASSERT_NE(user, nullptr);
    EXPECT_EQ(user->pw_gid, vibscore_gid());
    EXPECT_EQ(out_of("systemctl is-enabled vibscored"), "enabled\n");
    EXPECT_EQ(out_of("stat -c %U /var/lib/vibscore"), "vibscore\n");
}

TEST(SystemdGuest, DbusActivationStartsItAsUserVibscoreOnTheFirstCall) {
    ASSERT_EQ(sh("systemctl stop vibscored").exit_code, 0);
    EXPECT_EQ(sh("systemctl is-active vibscored").out, "inactive\n");
    const auto listed = as_alice(kBusctlObject + "List s score");
    ASSERT_EQ(listed.exit_code, 0) << listed.err;
    EXPECT_NE(listed.out.find("\"ringtone\""), std::string::npos);
    EXPECT_EQ(sh("systemctl is-active vibscored").out, "active\n");
    const auto uid = out_of("stat -c %U /proc/" + main_pid());
    EXPECT_EQ(uid, "vibscore\n");
}

// "FILE:LINE" of the installed configuration's driver = auto, as the daemon's reasons name it.
std::string auto_line() {
    auto line = out_of("grep -n '^driver = auto$' " + kConfig + " | cut -d: -f1");
    if (!line.empty() && line.back() == '\n') {
        line.pop_back();
    }
    return kConfig + ":" + line;
}

TEST(SystemdGuest, TheJournalHasItsMessages) {
    const auto journal = out_of("journalctl -u vibscored -b -o cat --no-pager");
    EXPECT_NE(journal.find("ready on org.vibscore.Haptics1"), std::string::npos) << journal;
    EXPECT_NE(journal.find("registry: "), std::string::npos) << journal;
    // Installed with no actuator in the guest, driver = auto runs sim, and warns saying so.
    const auto warnings = out_of("journalctl -u vibscored -b -p warning -o cat --no-pager");
    // The reason names the line of the file that says auto.
    EXPECT_NE(warnings.find("driver = auto (" + auto_line() +
                            ") found no actuator, so driver sim plays (nothing "
                            "vibrates). Searched: evdev: no force-feedback device in /dev/input"),
              std::string::npos)
        << warnings;
}

// Under systemd the daemon writes to the journal itself, with fields a person can query: root's
// StopAll is found by its CALLER_UID and REASON, not by grepping text.
TEST(SystemdGuest, TheJournalFindsALineByItsFields) {
    ASSERT_EQ(sh("vibscore stop --all").exit_code, 0);
    EXPECT_TRUE(eventually([] {
        return sh("journalctl -u vibscored -b CALLER_UID=0 REASON=stop-all -o cat --no-pager")
                   .out.find("uid 0 stopped every playback") != std::string::npos;
    })) << out_of("journalctl -u vibscored -b -o verbose --no-pager | tail -40");
    // The priority is the journal's own, not a "<6>" prefix in the text.
    EXPECT_EQ(out_of("journalctl -u vibscored -b -o cat --no-pager | grep -c '^<[0-7]>' || true"),
              "0\n");
}

// The package's driver = auto on a phone: the vibra is there before the packages are, the
// shipped udev rules tag it, and a fresh install plays on it with nothing configured.
TEST(SystemdGuest, AFreshInstallPlaysOnTheUdevTaggedVibraWithNoConfiguration) {
    auto options = UinputVibratorOptions::phone_vibrator();
    options.mark_as_vibra = false;  // the shipped rules must tag it
    UinputVibrator vibra(options);
    ASSERT_EQ(sh("udevadm settle").exit_code, 0);
    const auto node = vibra.event_node().string();
    const auto purged = sh("apt-get purge -y -q vibscored");
    ASSERT_EQ(purged.exit_code, 0) << purged.out << purged.err;
    ASSERT_NE(sh("test -e " + kConfig).exit_code, 0);
    const auto installed = sh("apt-get install -y -q /tmp/vibscored_*.deb");
    ASSERT_EQ(installed.exit_code, 0) << installed.out << installed.err;
    EXPECT_EQ(out_of("grep -c '^driver = auto$' " + kConfig), "1\n");

    const auto driver = as_alice("vibscore driver");
    EXPECT_EQ(driver.exit_code, 0) << driver.err;
    EXPECT_EQ(driver.out.rfind("driver evdev: ", 0), 0u) << driver.out;
    EXPECT_NE(driver.out.find("driver = auto (" + auto_line() + "): evdev on " + node +
                              ", the force-feedback device udev tags FEEDBACKD_TYPE=vibra"),
              std::string::npos)
        << driver.out;
    const auto played = as_alice("vibscore play touch-click --wait");
    EXPECT_EQ(played.exit_code, 0) << played.err;
    EXPECT_TRUE(vibra.wait_for([](const FfEvent& event) {
        return event.kind == FfEvent::Kind::Play && event.value > 0;
    })) << out_of("journalctl -u vibscored -b -o cat --no-pager | tail -20");
}

TEST(SystemdGuest, UdevTagsAUinputVibraThatTheDaemonDrivesAndStopLeavesOff) {
    auto options = UinputVibratorOptions::phone_vibrator();
    options.mark_as_vibra = false;  // the shipped rules must tag it
    UinputVibrator vibra(options);
    ASSERT_EQ(sh("udevadm settle").exit_code, 0);
    const auto node = vibra.event_node().string();
    EXPECT_NE(out_of("udevadm info --query=property --name=" + node).find("FEEDBACKD_TYPE=vibra"),
              std::string::npos);
    expect_vibscore_device(node);

    configure("driver = evdev\n");
    const auto played =
        sh(kBusctlObject + "Play sa{sv} ringtone 1 repeat i 1");  // busctl leaves at once
    ASSERT_EQ(played.exit_code, 0) << played.err;
    EXPECT_TRUE(vibra.wait_for([](const FfEvent& event) {
        return event.kind == FfEvent::Kind::Play && event.value > 0;
    })) << out_of("journalctl -u vibscored -b -o cat --no-pager | tail -20");
    ASSERT_EQ(sh("systemctl stop vibscored").exit_code, 0);
    EXPECT_TRUE(vibra.playing().empty());
    EXPECT_TRUE(vibra.effects().empty());
}

TEST(SystemdGuest, TheShippedRulesHandGroupVibscoreAGpioSimChipThatTheDaemonDrives) {
    GpioSimChip chip(GpioSimOptions{.lines = 2});
    ASSERT_EQ(sh("udevadm settle").exit_code, 0);
    expect_vibscore_device(chip.chip_path().string());
    configure("driver = gpio-erm\n[gpio-erm]\nchip = " + chip.chip_name() +
              "\nline = 0\ncarrier-hz = 100\n");
    const auto played = sh(kBusctlObject + "Play sa{sv} ringtone 0");
    ASSERT_EQ(played.exit_code, 0) << played.err;
    EXPECT_TRUE(eventually([&] { return chip.value(0) == 1; }, std::chrono::seconds(5)))
        << out_of("journalctl -u vibscored -b -o cat --no-pager | tail -20");
    ASSERT_EQ(sh("systemctl stop vibscored").exit_code, 0);
    EXPECT_EQ(chip.value(0), 0);
}

TEST(SystemdGuest, SystemctlReloadAppliesAChangedConfiguration) {
    configure("driver = sim\n");
    const auto pid = main_pid();
    const std::string bar_clefs = kBusctlObject + "BarClefs s success";
    EXPECT_EQ(out_of(bar_clefs), "a(ss) 1 \"lra-phone\" \"lra-phone\"\n");
    std::ofstream(kConfig, std::ios::app) << "[clefs]\nlra-phone = erm-phone\n";
    const auto reloaded = sh("systemctl reload vibscored");
    ASSERT_EQ(reloaded.exit_code, 0) << reloaded.err;
    EXPECT_EQ(out_of(bar_clefs), "a(ss) 1 \"lra-phone\" \"erm-phone\"\n");
    EXPECT_EQ(main_pid(), pid);
    EXPECT_NE(out_of("journalctl -u vibscored -b -o cat --no-pager")
                  .find("device clefs: lra-phone -> erm-phone"),
              std::string::npos);
}

TEST(SystemdGuest, PolkitRefusesAUserInNoSessionComposeAndUrgentUsagesAndRootMay) {
    const auto compose = as_alice(kBusctlObject + "Compose ss mine '" + kScore + "'");
    EXPECT_NE(compose.exit_code, 0);
    EXPECT_NE(compose.err.find("Compose needs org.vibscore.compose, which polkit does not grant"),
              std::string::npos)
        << compose.err;
    const auto ring = as_alice(kBusctlObject + "Play sa{sv} touch-click 1 usage s ringtone");
    EXPECT_NE(ring.err.find("needs org.vibscore.urgent-usage"), std::string::npos) << ring.err;
    const auto intensity = as_alice(kBusctlObject + "SetIntensity d 0.5");
    EXPECT_NE(intensity.err.find("org.vibscore.manage"), std::string::npos) << intensity.err;
    EXPECT_EQ(as_alice(kBusctlObject + "Play sa{sv} touch-click 0").exit_code, 0);

    const auto by_root = sh(kBusctlObject + "Compose ss mine '" + kScore + "'");
    EXPECT_EQ(by_root.exit_code, 0) << by_root.err;
    EXPECT_EQ(sh(kBusctlObject + "Play sa{sv} touch-click 1 usage s ringtone").exit_code, 0);
}

// alice logged in on the active virtual console, as logind sees a local login: polkit's
// allow_active defaults let her compose and ring.
TEST(SystemdGuest, PolkitAllowsTheActiveLocalSessionsUserComposeAndUrgentUsages) {
    const std::string script =
        "loginctl show-session --property=Active --property=Remote $XDG_SESSION_ID; " +
        kBusctlObject + "Compose ss alices '" + kScore + "' && echo composed; " + kBusctlObject +
        "Play sa{sv} touch-click 1 usage s ringtone && echo rang";
    const auto session = run_command(
        {"/usr/bin/systemd-run", "--wait", "--collect", "--quiet", "--property=PAMName=login",
         "--property=User=alice", "--property=TTYPath=/dev/tty1",
         "--property=StandardOutput=file:/tmp/session.out",
         "--property=StandardError=file:/tmp/session.err", "/bin/sh", "-c", script});
    const auto out = out_of("cat /tmp/session.out");
    EXPECT_EQ(session.exit_code, 0) << session.err << out << out_of("cat /tmp/session.err");
    EXPECT_NE(out.find("Active=yes\n"), std::string::npos) << out;
    EXPECT_NE(out.find("Remote=no\n"), std::string::npos) << out;
    EXPECT_NE(out.find("composed\n"), std::string::npos) << out << out_of("cat /tmp/session.err");
    EXPECT_NE(out.find("rang\n"), std::string::npos) << out;
}

TEST(SystemdGuest, AUserPlaysARingtoneWithWaitToItsEnd) {
    const auto played = as_alice("vibscore play ringtone --wait");
    EXPECT_EQ(played.exit_code, 0) << played.err;
    EXPECT_NE(played.out.find(" completed\n"), std::string::npos) << played.out;
}

// The store of composed documents survives an upgrade and a removal, and goes with a purge.
TEST(SystemdGuest, UpgradeAndRemoveKeepTheStoreAndPurgeDropsIt) {
    ASSERT_EQ(sh("test -f /var/lib/vibscore/mine.score.xml").exit_code, 0);
    const std::string debs = vibscore::testing::required_env("VIBSCORE_DEBS");
    // A newer version of the same package: the upgrade path of every maintainer script.
    const auto repacked =
        sh("set -e; rm -rf /tmp/up && mkdir /tmp/up && dpkg-deb -R " + debs +
           "/vibscored_*.deb /tmp/up/root && sed -i 's/^Version: .*/&+guest1/' "
           "/tmp/up/root/DEBIAN/control && dpkg-deb -b /tmp/up/root /tmp/up/vibscored_new.deb");
    ASSERT_EQ(repacked.exit_code, 0) << repacked.err;
    const auto upgraded = sh("apt-get install -y -q /tmp/up/vibscored_new.deb");
    ASSERT_EQ(upgraded.exit_code, 0) << upgraded.out << upgraded.err;
    EXPECT_NE(out_of("dpkg-query -W -f='${Version}' vibscored").find("+guest1"), std::string::npos);
    EXPECT_EQ(sh("test -f /var/lib/vibscore/mine.score.xml").exit_code, 0);
    EXPECT_EQ(sh("systemctl is-active vibscored").out, "active\n");

    ASSERT_EQ(sh("apt-get remove -y -q vibscored").exit_code, 0);
    EXPECT_EQ(sh("test -f /var/lib/vibscore/mine.score.xml").exit_code, 0);
    EXPECT_EQ(sh("test -f " + kConfig).exit_code, 0);  // a conffile stays until purge
    EXPECT_NE(sh("test -e /usr/sbin/vibscored").exit_code, 0);

    ASSERT_EQ(sh("apt-get purge -y -q vibscored").exit_code, 0);
    EXPECT_NE(sh("test -e /var/lib/vibscore").exit_code, 0);
    EXPECT_NE(sh("test -e " + kConfig).exit_code, 0);
}

}  // namespace
}  // namespace vibscore::hil
