#include "daemon/drivers/evdev_discovery.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "daemon/drivers/actuator.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using vibscore::testing::TempDir;

// A /dev/input of plain files and a udev database beside it. The probe answers for the files by
// name: which have force feedback, which cannot be opened, and the device numbers the kernel
// would give eventN (13:64+N).
struct FakeInputTree {
    TempDir root;
    fs::path input_dir = root.path() / "input";
    fs::path udev_data = root.path() / "udev";
    std::set<std::string> with_ff;
    std::set<std::string> unreadable;
    std::vector<std::string> probed;

    FakeInputTree() {
        fs::create_directories(input_dir);
        fs::create_directories(udev_data);
    }

    void node(const std::string& name, bool ff = false) {
        root.write("input/" + name, "");
        if (ff) {
            with_ff.insert(name);
        }
    }

    void udev_entry(unsigned event, const std::string& text) {
        root.write("udev/c13:" + std::to_string(64 + event), text);
    }

    DiscoverySettings settings() const { return {input_dir, udev_data}; }

    DiscoveryProbe probe() {
        return {
            [this](const fs::path& path) {
                const std::string name = path.filename().string();
                probed.push_back(name);
                if (unreadable.count(name)) {
                    return FfProbeResult::unreadable;
                }
                return with_ff.count(name) ? FfProbeResult::force_feedback
                                           : FfProbeResult::no_force_feedback;
            },
            [](const fs::path& path) -> std::optional<CharDeviceNumber> {
                const std::string name = path.filename().string();
                return CharDeviceNumber{13, 64 + static_cast<unsigned>(std::stoul(name.substr(5)))};
            },
        };
    }

    fs::path discover() { return discover_ff_device(settings(), probe()).path; }
};

constexpr const char* vibra_entry =
    "I:1234\nE:ID_INPUT=1\nE:FEEDBACKD_TYPE=vibra\nG:seat\nQ:seat\nV:1\n";

TEST(EvdevDiscovery, PrefersTheDeviceUdevTagsAsVibra) {
    FakeInputTree tree;
    tree.node("event0", true);  // a gamepad's rumble, found first
    tree.node("event1");
    tree.node("event4", true);
    tree.udev_entry(0, "E:ID_INPUT_JOYSTICK=1\n");
    tree.udev_entry(4, vibra_entry);
    const DiscoveredDevice found = discover_ff_device(tree.settings(), tree.probe());
    EXPECT_EQ(found.path, tree.input_dir / "event4");
    EXPECT_TRUE(found.tagged_vibra);
}

TEST(EvdevDiscovery, WithoutATagTakesTheFirstForceFeedbackDeviceInNumericOrder) {
    FakeInputTree tree;
    tree.node("event10", true);
    tree.node("event2", true);
    tree.node("event1");
    const DiscoveredDevice found = discover_ff_device(tree.settings(), tree.probe());
    EXPECT_EQ(found.path, tree.input_dir / "event2");
    EXPECT_FALSE(found.tagged_vibra);
}

TEST(EvdevDiscovery, TheTagCountsOnlyOnADeviceWithForceFeedback) {
    FakeInputTree tree;
    tree.node("event0");  // tagged, but the probe finds no EV_FF
    tree.node("event3", true);
    tree.udev_entry(0, vibra_entry);
    EXPECT_EQ(tree.discover(), tree.input_dir / "event3");
}

TEST(EvdevDiscovery, OnlyTheExactVibraLineCounts) {
    FakeInputTree tree;
    tree.node("event0", true);
    tree.node("event1", true);
    tree.node("event2", true);
    tree.node("event3", true);
    tree.udev_entry(1, "E:FEEDBACKD_TYPE=vibrator\n");
    tree.udev_entry(2, "E:FEEDBACKD_TYPE=led\nE:X_FEEDBACKD_TYPE=vibra\n");
    tree.udev_entry(3, "E:FEEDBACKD_TYPE=vibra");  // no final newline
    EXPECT_EQ(tree.discover(), tree.input_dir / "event3");
}

TEST(EvdevDiscovery, IgnoresEverythingButEventNodes) {
    FakeInputTree tree;
    tree.node("mouse0", true);
    tree.node("js0", true);
    tree.node("eventX", true);
    tree.node("event", true);
    fs::create_directories(tree.input_dir / "by-path");
    tree.node("event7", true);
    EXPECT_EQ(tree.discover(), tree.input_dir / "event7");
    EXPECT_EQ(tree.probed, std::vector<std::string>{"event7"});
}

TEST(EvdevDiscovery, DeviceWithoutADeviceNumberIsStillACandidate) {
    FakeInputTree tree;
    tree.node("event0", true);
    DiscoveryProbe probe = tree.probe();
    probe.device_number = [](const fs::path&) { return std::optional<CharDeviceNumber>(); };
    EXPECT_EQ(discover_ff_device(tree.settings(), probe).path, tree.input_dir / "event0");
}

TEST(EvdevDiscovery, NothingFoundSaysWhereItLookedAndWhatItSaw) {
    FakeInputTree tree;
    tree.node("event0");
    tree.node("event1");
    tree.node("event2");
    tree.unreadable.insert("event2");
    try {
        tree.discover();
        FAIL() << "no exception";
    } catch (const DeviceError& error) {
        EXPECT_STREQ(error.what(),
                     ("evdev: no force-feedback device in " + tree.input_dir.string() +
                      " (3 event devices, none with force feedback; 1 could not "
                      "be opened (permissions?))")
                         .c_str());
    }
}

TEST(EvdevDiscovery, EmptyDirectory) {
    FakeInputTree tree;
    try {
        tree.discover();
        FAIL() << "no exception";
    } catch (const DeviceError& error) {
        EXPECT_THAT(error.what(), HasSubstr("(0 event devices, none with force feedback)"));
    }
}

TEST(EvdevDiscovery, MissingDirectoryIsNamed) {
    FakeInputTree tree;
    DiscoverySettings settings = tree.settings();
    settings.input_dir = tree.root.path() / "nowhere";
    try {
        discover_ff_device(settings, tree.probe());
        FAIL() << "no exception";
    } catch (const DeviceError& error) {
        EXPECT_THAT(error.what(), HasSubstr("cannot search " + settings.input_dir.string()));
        EXPECT_THAT(error.what(), HasSubstr("No such file or directory"));
    }
}

TEST(EvdevDiscovery, KernelProbeReadsTheDeviceNumberOfCharacterDevices) {
    const DiscoveryProbe probe = kernel_discovery_probe();
    const auto null = probe.device_number("/dev/null");  // 1:3 on every Linux
    ASSERT_TRUE(null.has_value());
    EXPECT_EQ(null->major, 1u);
    EXPECT_EQ(null->minor, 3u);
    TempDir dir;
    EXPECT_FALSE(probe.device_number(dir.write("event0", "")).has_value());
    EXPECT_FALSE(probe.device_number(dir.path() / "missing").has_value());
}

TEST(EvdevDiscovery, KernelProbeSeesNoForceFeedbackInOtherFiles) {
    const DiscoveryProbe probe = kernel_discovery_probe();
    EXPECT_EQ(probe.force_feedback("/dev/null"), FfProbeResult::no_force_feedback);
    TempDir dir;
    EXPECT_EQ(probe.force_feedback(dir.write("event0", "")), FfProbeResult::no_force_feedback);
    EXPECT_EQ(probe.force_feedback(dir.path() / "missing"), FfProbeResult::unreadable);
}

}  // namespace
}  // namespace vibscore::drivers
