// The evdev force-feedback interface end to end, without the daemon: a client of
// /dev/input/eventN (libevdev and the FF ioctls) against a UinputVibrator.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "common/unique_fd.hpp"
#include "tests/hil/uinput_vibrator.hpp"

namespace vibscore::hil {
namespace {

using Kind = FfEvent::Kind;
using EvdevPtr = std::unique_ptr<libevdev, decltype(&libevdev_free)>;

UniqueFd open_node(const std::filesystem::path& node) {
    UniqueFd fd(::open(node.c_str(), O_RDWR | O_CLOEXEC));
    EXPECT_GE(fd.get(), 0) << node << ": " << std::strerror(errno);
    return fd;
}

EvdevPtr evdev_of(const UniqueFd& fd) {
    libevdev* device = nullptr;
    EXPECT_EQ(libevdev_new_from_fd(fd.get(), &device), 0);
    return {device, &libevdev_free};
}

ff_effect sine(std::uint16_t period_ms, std::int16_t magnitude, std::uint16_t length_ms) {
    ff_effect effect{};
    effect.type = FF_PERIODIC;
    effect.id = -1;
    effect.u.periodic.waveform = FF_SINE;
    effect.u.periodic.period = period_ms;
    effect.u.periodic.magnitude = magnitude;
    effect.u.periodic.envelope.attack_length = 5;
    effect.u.periodic.envelope.attack_level = 0x1000;
    effect.replay.length = length_ms;
    return effect;
}

void write_ff(const UniqueFd& fd, std::uint16_t code, std::int32_t value) {
    input_event event{};
    event.type = EV_FF;
    event.code = code;
    event.value = value;
    ASSERT_EQ(::write(fd.get(), &event, sizeof event), static_cast<ssize_t>(sizeof event))
        << std::strerror(errno);
}

std::vector<Kind> kinds(const std::vector<FfEvent>& timeline) {
    std::vector<Kind> result;
    for (const auto& event : timeline) {
        result.push_back(event.kind);
    }
    return result;
}

std::string listing(const std::vector<FfEvent>& timeline) {
    std::ostringstream out;
    for (const auto& event : timeline) {
        out << "\n  " << event;
    }
    return out.str();
}

TEST(EvdevSmoke, TheDeviceShowsItsForceFeedbackCapabilities) {
    UinputVibratorOptions options;
    options.effects_max = 8;
    UinputVibrator vibrator(options);
    const auto fd = open_node(vibrator.event_node());
    const auto device = evdev_of(fd);
    EXPECT_STREQ(libevdev_get_name(device.get()), "vibscore-hil-vibrator");
    EXPECT_TRUE(libevdev_has_event_code(device.get(), EV_FF, FF_PERIODIC));
    EXPECT_TRUE(libevdev_has_event_code(device.get(), EV_FF, FF_SINE));
    EXPECT_TRUE(libevdev_has_event_code(device.get(), EV_FF, FF_GAIN));
    EXPECT_FALSE(libevdev_has_event_code(device.get(), EV_FF, FF_CONSTANT));
    int effects = 0;
    ASSERT_EQ(::ioctl(fd.get(), EVIOCGEFFECTS, &effects), 0);
    EXPECT_EQ(effects, 8);
}

TEST(EvdevSmoke, UploadGainPlayStopEraseArriveInOrder) {
    UinputVibrator vibrator;
    {
        const auto fd = open_node(vibrator.event_node());
        auto effect = sine(5, 0x6000, 300);
        ASSERT_EQ(::ioctl(fd.get(), EVIOCSFF, &effect), 0) << std::strerror(errno);
        ASSERT_GE(effect.id, 0);
        write_ff(fd, FF_GAIN, 0xC000);
        write_ff(fd, static_cast<std::uint16_t>(effect.id), 1);
        ASSERT_TRUE(vibrator.wait_for([&](const FfEvent& e) { return e.kind == Kind::Play; }));
        EXPECT_EQ(vibrator.playing(), std::set<int>{effect.id});
        write_ff(fd, static_cast<std::uint16_t>(effect.id), 0);
        ASSERT_EQ(::ioctl(fd.get(), EVIOCRMFF, effect.id), 0) << std::strerror(errno);

        const auto timeline = vibrator.timeline();
        // The kernel stops an effect itself before erasing it: the second play-stop.
        ASSERT_EQ(kinds(timeline),
                  (std::vector<Kind>{Kind::Created, Kind::Upload, Kind::Gain, Kind::Play,
                                     Kind::Play, Kind::Play, Kind::Erase}))
            << listing(timeline);
        const auto& upload = timeline[1];
        EXPECT_EQ(upload.effect_id, effect.id);
        EXPECT_EQ(upload.value, 0);
        EXPECT_EQ(upload.effect.type, FF_PERIODIC);
        EXPECT_EQ(upload.effect.u.periodic.waveform, FF_SINE);
        EXPECT_EQ(upload.effect.u.periodic.period, 5);
        EXPECT_EQ(upload.effect.u.periodic.magnitude, 0x6000);
        EXPECT_EQ(upload.effect.u.periodic.envelope.attack_length, 5);
        EXPECT_EQ(upload.effect.replay.length, 300);
        EXPECT_EQ(timeline[2].value, 0xC000);
        EXPECT_EQ(timeline[3].effect_id, effect.id);
        EXPECT_EQ(timeline[3].value, 1);
        EXPECT_EQ(timeline[4].value, 0);
        EXPECT_EQ(timeline[6].effect_id, effect.id);
        for (std::size_t i = 1; i < timeline.size(); ++i) {
            EXPECT_LE(timeline[i - 1].time, timeline[i].time) << listing(timeline);
        }
        EXPECT_TRUE(vibrator.effects().empty());
        EXPECT_TRUE(vibrator.playing().empty());
    }
}

TEST(EvdevSmoke, ClosingTheClientStopsAndErasesItsEffects) {
    UinputVibrator vibrator;
    int id = -1;
    {
        const auto fd = open_node(vibrator.event_node());
        auto effect = sine(10, 0x7fff, 1000);
        ASSERT_EQ(::ioctl(fd.get(), EVIOCSFF, &effect), 0) << std::strerror(errno);
        id = effect.id;
        write_ff(fd, static_cast<std::uint16_t>(id), 1);
        ASSERT_TRUE(vibrator.wait_for([](const FfEvent& e) { return e.kind == Kind::Play; }));
        vibrator.clear_timeline();
    }  // close() waits for the fixture's answer to the erase the kernel sends
    const auto timeline = vibrator.timeline();
    ASSERT_EQ(kinds(timeline), (std::vector<Kind>{Kind::Play, Kind::Erase})) << listing(timeline);
    EXPECT_EQ(timeline[0].effect_id, id);
    EXPECT_EQ(timeline[0].value, 0);
    EXPECT_EQ(timeline[1].effect_id, id);
    EXPECT_TRUE(vibrator.effects().empty());
}

TEST(EvdevSmoke, AnUploadTheDeviceRefusesFailsWithItsErrno) {
    UinputVibrator vibrator;
    vibrator.answer_uploads_with(ENOSPC);
    const auto fd = open_node(vibrator.event_node());
    auto effect = sine(5, 0x4000, 100);
    EXPECT_EQ(::ioctl(fd.get(), EVIOCSFF, &effect), -1);
    EXPECT_EQ(errno, ENOSPC);
    EXPECT_TRUE(vibrator.effects().empty());
    vibrator.answer_uploads_with(0);
    effect.id = -1;
    EXPECT_EQ(::ioctl(fd.get(), EVIOCSFF, &effect), 0) << std::strerror(errno);
    EXPECT_EQ(vibrator.effects().size(), 1u);
}

TEST(EvdevSmoke, ARemovedDeviceFailsItsClientsAndComesBackWithANewNode) {
    UinputVibrator vibrator(UinputVibratorOptions::phone_vibrator());
    const auto fd = open_node(vibrator.event_node());
    {
        const auto device = evdev_of(fd);
        EXPECT_STREQ(libevdev_get_name(device.get()), "pm8xxx-vibrator");
        EXPECT_EQ(libevdev_get_id_bustype(device.get()), BUS_HOST);
        EXPECT_FALSE(libevdev_has_event_type(device.get(), EV_KEY));
        EXPECT_TRUE(libevdev_has_event_code(device.get(), EV_FF, FF_RUMBLE));
    }
    struct stat node {};
    ASSERT_EQ(::stat(vibrator.event_node().c_str(), &node), 0);
    EXPECT_EQ(vibrator.udev_entry(), "/run/udev/data/c13:" + std::to_string(minor(node.st_rdev)));
    std::ifstream entry(vibrator.udev_entry());
    std::string line;
    EXPECT_TRUE(std::getline(entry, line));
    EXPECT_EQ(line, "E:FEEDBACKD_TYPE=vibra");

    const auto old_node = vibrator.event_node();
    const auto old_entry = vibrator.udev_entry();
    vibrator.destroy();
    EXPECT_FALSE(std::filesystem::exists(old_node));
    EXPECT_FALSE(std::filesystem::exists(old_entry));
    input_event play{};
    play.type = EV_FF;
    play.value = 1;
    EXPECT_EQ(::write(fd.get(), &play, sizeof play), -1);
    EXPECT_EQ(errno, ENODEV);

    vibrator.recreate();
    ASSERT_TRUE(std::filesystem::exists(vibrator.event_node()));
    const auto again = open_node(vibrator.event_node());
    auto effect = sine(5, 0x4000, 100);
    EXPECT_EQ(::ioctl(again.get(), EVIOCSFF, &effect), 0) << std::strerror(errno);
    const auto timeline = vibrator.timeline();
    EXPECT_EQ(kinds(timeline),
              (std::vector<Kind>{Kind::Created, Kind::Destroyed, Kind::Created, Kind::Upload}))
        << listing(timeline);
}

}  // namespace
}  // namespace vibscore::hil
