// vibscored's virtual vibra in the guest, on the real uinput and evdev: force-feedback clients
// (plain EVIOCSFF/EV_FF as fftest and games do, Debian's fftest, Debian's feedbackd driven by
// fbcli) upload and play effects on it, and the simulated actuator's trace shows what
// vibscored played for them.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <libevdev/libevdev.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <optional>
#include <thread>

#include "common/unique_fd.hpp"
#include "daemon/drivers/evdev_discovery.hpp"
#include "tests/hil/virtual_vibra_node.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/feedback_fixture.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::DaemonFixture;
using testing::SeenSignal;
using TraceRow = DaemonFixture::TraceRow;

constexpr const char* kVibraConfig = "\n[virtual-vibra]\nenabled = true\nusage = notification\n";

// A force-feedback client as fftest or a game is one: its own open file of the event node.
class FfClient {
  public:
    explicit FfClient(const fs::path& node) : fd_(::open(node.c_str(), O_RDWR | O_CLOEXEC)) {}
    bool is_open() const { return fd_.get() >= 0; }
    // The id the kernel gave, or -errno.
    int upload(ff_effect effect) {
        effect.id = -1;
        return ::ioctl(fd_.get(), EVIOCSFF, &effect) < 0 ? -errno : effect.id;
    }
    void send(std::uint16_t code, std::int32_t value) {
        input_event event{};
        event.type = EV_FF;
        event.code = code;
        event.value = value;
        ASSERT_EQ(::write(fd_.get(), &event, sizeof event), static_cast<ssize_t>(sizeof event))
            << std::strerror(errno);
    }
    void close() { fd_ = UniqueFd(); }

  private:
    UniqueFd fd_;
};

ff_effect rumble(std::uint16_t strong, std::uint16_t length_ms) {
    ff_effect effect{};
    effect.type = FF_RUMBLE;
    effect.u.rumble.strong_magnitude = strong;
    effect.replay.length = length_ms;
    return effect;
}

ff_effect periodic(std::uint16_t waveform, std::uint16_t period_ms, std::uint16_t length_ms) {
    ff_effect effect{};
    effect.type = FF_PERIODIC;
    effect.u.periodic.waveform = waveform;
    effect.u.periodic.period = period_ms;
    effect.u.periodic.magnitude = 0x7fff;
    effect.replay.length = length_ms;
    return effect;
}

double loudest(const std::vector<TraceRow>& rows, std::size_t from) {
    double level = 0.0;
    for (std::size_t i = from; i < rows.size(); ++i) {
        level = std::max(level, rows[i].amplitude);
    }
    return level;
}

// Seconds from the first drive after `from` to the next drive of 0.
double sounding_seconds(const std::vector<TraceRow>& rows, std::size_t from) {
    for (std::size_t i = from; i < rows.size(); ++i) {
        if (rows[i].amplitude > 0.0) {
            for (std::size_t j = i + 1; j < rows.size(); ++j) {
                if (rows[j].amplitude == 0.0) {
                    return static_cast<double>(rows[j].time_ns - rows[i].time_ns) / 1e9;
                }
            }
            return -1.0;
        }
    }
    return 0.0;
}

class VirtualVibraTest : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!fs::exists("/dev/uinput")) {
            GTEST_SKIP() << "no /dev/uinput";
        }
        node = find_virtual_vibra();
        ASSERT_TRUE(node) << daemon.daemon_log();
    }

    // Waits for the virtual vibra's next playback to start and finish; its id, or 0.
    std::uint64_t played(std::string* reason = nullptr, std::string* label = nullptr) {
        std::uint64_t id = 0;
        const bool started = client->wait_for([&](const SeenSignal& signal) {
            if (signal.name == "PlaybackStarted" && signal.text.starts_with("virtual-vibra") &&
                signal.id > last_id) {
                id = signal.id;
                if (label != nullptr) {
                    *label = signal.text;
                }
                return true;
            }
            return false;
        });
        if (!started || !client->wait_finished(id, reason)) {
            return 0;
        }
        last_id = id;
        return id;
    }

    DaemonFixture daemon{kVibraConfig};
    std::unique_ptr<testing::HapticsClient> client = daemon.client();
    std::optional<fs::path> node;
    std::uint64_t last_id = 0;
};

TEST_F(VirtualVibraTest, AdvertisesWhatFeedbackdAndGamesAskFor) {
    UniqueFd fd(::open(node->c_str(), O_RDONLY | O_CLOEXEC));
    libevdev* raw = nullptr;
    ASSERT_EQ(libevdev_new_from_fd(fd.get(), &raw), 0);
    std::unique_ptr<libevdev, decltype(&libevdev_free)> device(raw, &libevdev_free);
    for (const int code :
         {FF_RUMBLE, FF_PERIODIC, FF_SINE, FF_SQUARE, FF_TRIANGLE, FF_CONSTANT, FF_GAIN}) {
        EXPECT_TRUE(libevdev_has_event_code(device.get(), EV_FF, code)) << code;
    }
    EXPECT_EQ(drivers::kernel_discovery_probe().force_feedback(*node),
              drivers::FfProbeResult::no_force_feedback)
        << "vibscored's evdev discovery must never drive its own virtual vibra";
}

// What udev would make of the device with the rule vibscore ships, and without it (feedbackd's
// own rule wants a platform vibrator): udevadm test runs the rules without udevd.
TEST_F(VirtualVibraTest, TheShippedUdevRuleTagsItForFeedbackd) {
    const fs::path rules_dir = "/run/udev/rules.d";
    const fs::path rule = testing::required_env("VIBSCORE_UDEV_RULES");
    const auto device = fs::canonical(fs::path("/sys/class/input") / node->filename());
    const auto udev_properties = [&] {
        return testing::run_command({"/usr/bin/udevadm", "test", "--action=add", device.string()});
    };
    const auto without = udev_properties();
    ASSERT_EQ(without.exit_code, 0) << without.err;
    EXPECT_NE(without.out.find("ID_INPUT=1"), std::string::npos) << without.out;
    EXPECT_EQ(without.out.find("FEEDBACKD_TYPE=vibra"), std::string::npos) << without.out;
    fs::create_directories(rules_dir);
    fs::copy_file(rule, rules_dir / rule.filename(), fs::copy_options::overwrite_existing);
    const auto with = udev_properties();
    fs::remove(rules_dir / rule.filename());
    EXPECT_EQ(with.exit_code, 0) << with.err;
    EXPECT_NE(with.out.find("FEEDBACKD_TYPE=vibra"), std::string::npos) << with.out << with.err;
}

TEST_F(VirtualVibraTest, EachEffectTypePlaysOnTheActuator) {
    FfClient ff(*node);
    ASSERT_TRUE(ff.is_open());

    auto mark = daemon.trace_rows().size();
    const int rumble_id = ff.upload(rumble(0x8000, 200));
    ASSERT_GE(rumble_id, 0) << std::strerror(-rumble_id);
    ff.send(static_cast<std::uint16_t>(rumble_id), 1);
    std::string reason;
    ASSERT_NE(played(&reason), 0u) << daemon.daemon_log();
    EXPECT_EQ(reason, "completed");
    auto rows = daemon.trace_rows();
    EXPECT_NEAR(loudest(rows, mark), 0.5, 0.01);
    EXPECT_NEAR(sounding_seconds(rows, mark), 0.2, 0.05);

    for (const auto waveform : {FF_SINE, FF_SQUARE, FF_TRIANGLE}) {
        mark = daemon.trace_rows().size();
        const int id = ff.upload(periodic(waveform, 5, 100));
        ASSERT_GE(id, 0) << waveform << ": " << std::strerror(-id);
        ff.send(static_cast<std::uint16_t>(id), 1);
        ASSERT_NE(played(), 0u) << waveform << daemon.daemon_log();
        rows = daemon.trace_rows();
        ASSERT_GT(rows.size(), mark);
        EXPECT_NEAR(loudest(rows, mark), 1.0, 0.01) << waveform;
        EXPECT_EQ(rows[mark].frequency_hz, 200.0) << "a 5 ms period: " << waveform;
    }

    // A constant force with an attack from nothing: a rising ramp, then held, then off.
    ff_effect constant{};
    constant.type = FF_CONSTANT;
    constant.u.constant.level = 0x7fff;
    constant.u.constant.envelope.attack_length = 100;
    constant.replay.length = 200;
    mark = daemon.trace_rows().size();
    const int constant_id = ff.upload(constant);
    ASSERT_GE(constant_id, 0) << std::strerror(-constant_id);
    ff.send(static_cast<std::uint16_t>(constant_id), 1);
    ASSERT_NE(played(), 0u) << daemon.daemon_log();
    rows = daemon.trace_rows();
    ASSERT_GT(rows.size(), mark + 3);
    EXPECT_LT(rows[mark].amplitude, 0.2) << "the ramp starts low";
    EXPECT_NEAR(loudest(rows, mark), 1.0, 0.01);
}

TEST_F(VirtualVibraTest, RepeatCountAndGainApply) {
    FfClient ff(*node);
    ff.send(FF_GAIN, 0x8000);
    auto mark = daemon.trace_rows().size();
    const int id = ff.upload(rumble(0xffff, 50));
    ASSERT_GE(id, 0);
    ff.send(static_cast<std::uint16_t>(id), 3);
    ASSERT_NE(played(), 0u) << daemon.daemon_log();
    const auto rows = daemon.trace_rows();
    EXPECT_NEAR(loudest(rows, mark), 0.5, 0.01) << "gain 0x8000 halves the full rumble";
    int onsets = 0;
    for (std::size_t i = mark; i < rows.size(); ++i) {
        onsets += rows[i].amplitude > 0 && (i == mark || rows[i - 1].amplitude == 0) ? 1 : 0;
    }
    EXPECT_EQ(onsets, 3);
}

TEST_F(VirtualVibraTest, AClientClosingItsFileLeavesNothingPlaying) {
    FfClient ff(*node);
    const int id = ff.upload(rumble(0xffff, 0));  // until stopped
    ASSERT_GE(id, 0);
    ff.send(static_cast<std::uint16_t>(id), 1);
    ASSERT_TRUE(client->wait_for([](const SeenSignal& signal) {
        return signal.name == "PlaybackStarted" && signal.text.starts_with("virtual-vibra");
    })) << daemon.daemon_log();
    // Closed while it drives the actuator, not before the first drive.
    ASSERT_TRUE(vibscore::testing::wait_until([&] {
        return loudest(daemon.trace_rows(), 0) > 0.0;
    })) << daemon.daemon_log();
    ff.close();
    ASSERT_TRUE(client->wait_for(
        [](const SeenSignal& signal) { return signal.name == "PlaybackFinished"; }, 3s))
        << daemon.daemon_log();
    EXPECT_EQ(daemon.trace_rows().back().amplitude, 0.0);
}

TEST_F(VirtualVibraTest, ShutdownUnplugsTheDevice) {
    FfClient ff(*node);
    EXPECT_EQ(daemon.stop_daemon(), 0) << daemon.daemon_log();
    EXPECT_EQ(ff.upload(rumble(0xffff, 100)), -ENODEV);
    EXPECT_FALSE(fs::exists(*node));
}

TEST_F(VirtualVibraTest, DebiansFftestPlaysItsRumble) {
    if (!fs::exists("/usr/bin/fftest")) {
        GTEST_SKIP() << "no fftest (package joystick)";
    }
    testing::TempDir dir;
    testing::Process fftest({"/usr/bin/stdbuf", "-oL", "/usr/bin/fftest", node->string()},
                            dir.path() / "fftest.log", true);
    // fftest sets the gain to 75 %, uploads its effects, then plays the one whose number it
    // reads: 4 is the strong rumble (0x8000 for 5 s after 1 s). What the device cannot do
    // (spring, damper) the kernel refuses, and fftest reports it.
    // fftest asks for the number once its effects are uploaded; its stdout is a file, so it is
    // line-buffered (stdbuf) for the question to show when it is asked.
    ASSERT_TRUE(vibscore::testing::wait_until_file_contains(dir.path() / "fftest.log",
                                                            "Enter effect number"))
        << testing::read_file(dir.path() / "fftest.log");
    fftest.write_stdin("4\n");
    ASSERT_TRUE(client->wait_for([](const SeenSignal& signal) {
        return signal.name == "PlaybackStarted" && signal.text.starts_with("virtual-vibra");
    })) << testing::read_file(dir.path() / "fftest.log")
        << daemon.daemon_log();
    // The rumble starts 1 s after the play: wait until it drives the actuator.
    vibscore::testing::wait_until([&] { return loudest(daemon.trace_rows(), 0) > 0.0; });
    const auto rows = daemon.trace_rows();
    // 0x8000 of 0xffff, at the master gain of 75 % fftest sets first.
    EXPECT_NEAR(loudest(rows, 0), 0.375, 0.01) << testing::read_file(dir.path() / "fftest.log");
    fftest.signal(SIGTERM);
    fftest.wait();
    ASSERT_TRUE(client->wait_for(
        [](const SeenSignal& signal) { return signal.name == "PlaybackFinished"; }, 3s))
        << "fftest's end erased its effects" << daemon.daemon_log();
}

// A rumble as games and tools write it with python-evdev (Debian's python3-evdev): upload, play,
// erase when done.
constexpr const char* kPythonRumble = R"(
import sys, time
import evdev
from evdev import ecodes, ff
device = evdev.InputDevice(sys.argv[1])
rumble = ff.Rumble(strong_magnitude=0, weak_magnitude=0xc000)
effect = ff.Effect(ecodes.FF_RUMBLE, -1, 0, ff.Trigger(0, 0), ff.Replay(120, 0),
                   ff.EffectType(ff_rumble_effect=rumble))
effect_id = device.upload_effect(effect)
device.write(ecodes.EV_FF, effect_id, 1)
time.sleep(0.5)
device.erase_effect(effect_id)
)";

TEST_F(VirtualVibraTest, APythonEvdevClientsRumblePlays) {
    if (!fs::exists("/usr/lib/python3/dist-packages/evdev")) {
        GTEST_SKIP() << "no python3-evdev";
    }
    const auto result = testing::run_command({"/usr/bin/python3", "-c", kPythonRumble, *node});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    std::string reason, label;
    ASSERT_NE(played(&reason, &label), 0u) << daemon.daemon_log();
    EXPECT_TRUE(label.ends_with(": rumble 120 ms")) << label;
    EXPECT_EQ(reason, "completed");
    const auto rows = daemon.trace_rows();
    EXPECT_NEAR(loudest(rows, 0), 0.75, 0.01) << "the weak motor at 0xc000";
    EXPECT_NEAR(sounding_seconds(rows, 0), 0.12, 0.05);
}

TEST_F(VirtualVibraTest, DebiansFeedbackdDrivesItForFbcli) {
    if (!fs::exists("/usr/libexec/feedbackd")) {
        GTEST_SKIP() << "no feedbackd";
    }
    // feedbackd finds its vibra in udev's database (docs/feedbackd.md): without udevd in the
    // guest, write what udev/61-vibscore-virtual-vibra.rules would have stored.
    std::optional<FeedbackdVibraMark> mark(std::in_place, *node);
    testing::SessionBus bus;
    testing::FeedbackServer feedbackd(bus, testing::real_feedbackd());
    testing::Fbcli fbcli(bus, {"-E", "message-new-instant"});  // VibraRumble, 150 ms
    std::string reason, label;
    const auto id = played(&reason, &label);
    mark.reset();
    ASSERT_NE(id, 0u) << feedbackd.log() << fbcli.output() << daemon.daemon_log();
    EXPECT_TRUE(label.ends_with(": rumble 150 ms")) << label;
    const auto rows = daemon.trace_rows();
    // 0x8000 (feedbackd's rumble) at the gain of 0xc000 it sets when it opens a vibra.
    EXPECT_NEAR(loudest(rows, 0), 0.375, 0.01);
    // feedbackd erases the effect 150 ms after it played it, by its own clock: under the
    // guest's emulation that can come before vibscored's 150 ms are over, and stops it, as it
    // stops an ff-memless vibra.
    const double seconds = sounding_seconds(rows, 0);
    if (reason == "completed") {
        EXPECT_NEAR(seconds, 0.15, 0.05);
    } else {
        EXPECT_EQ(reason, "stopped");
        EXPECT_GT(seconds, 0.0);
        EXPECT_LT(seconds, 0.2);
    }
    fbcli.kill();
}

}  // namespace
}  // namespace vibscore::hil
