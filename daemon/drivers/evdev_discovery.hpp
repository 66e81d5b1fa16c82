#pragma once

#include <filesystem>
#include <functional>
#include <optional>

namespace vibscore::drivers {

// Where to look for a force-feedback device when none is configured. Both are settings so that
// tests (and unusual systems) can point them elsewhere.
struct DiscoverySettings {
    std::filesystem::path input_dir = "/dev/input";
    std::filesystem::path udev_data = "/run/udev/data";  // udev's database: c<major>:<minor>
};

// What a look at one event node found.
enum class FfProbeResult {
    force_feedback,     // EV_FF with an effect the evdev backend can play
    no_force_feedback,  // an event device without (usable) force feedback, or not one at all
    unreadable,         // could not be opened, e.g. no permission
};

struct CharDeviceNumber {
    unsigned major = 0;
    unsigned minor = 0;
};

// The two questions discovery asks about a node; the kernel answers them in the daemon, a test
// answers them for the plain files of a temporary tree.
struct DiscoveryProbe {
    std::function<FfProbeResult(const std::filesystem::path&)> force_feedback;
    std::function<std::optional<CharDeviceNumber>(const std::filesystem::path&)> device_number;
};

// The phys of the virtual vibra vibscored serves itself (daemon/virtual_vibra): a force-feedback
// device it must never drive, or it would play into itself.
inline constexpr const char* kVirtualVibraPhys = "vibscore/virtual-vibra";

// Opens the node read-only and asks libevdev for EV_FF with FF_RUMBLE, or FF_PERIODIC with
// FF_SINE or FF_SQUARE, and for a phys other than kVirtualVibraPhys; the device number comes
// from stat's st_rdev (character devices only).
DiscoveryProbe kernel_discovery_probe();

struct DiscoveredDevice {
    std::filesystem::path path;
    bool tagged_vibra = false;  // udev marked it E:FEEDBACKD_TYPE=vibra
};

// Picks the force-feedback device among the eventN nodes of settings.input_dir: the first (by N)
// whose udev database entry carries E:FEEDBACKD_TYPE=vibra (as feedbackd's udev rules set it),
// otherwise the first with force feedback at all. Throws DeviceError saying where it looked and
// what it found when there is none.
DiscoveredDevice discover_ff_device(const DiscoverySettings& settings, const DiscoveryProbe& probe);

}  // namespace vibscore::drivers
