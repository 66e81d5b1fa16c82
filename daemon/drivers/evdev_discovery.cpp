#include "daemon/drivers/evdev_discovery.hpp"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "common/evdev_node.hpp"
#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

namespace fs = std::filesystem;

namespace {

// N of an "eventN" name, nothing for any other name (mice, js, by-id directories...).
std::optional<unsigned> event_number(const std::string& name) {
    constexpr std::string_view prefix = "event";
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) {
        return std::nullopt;
    }
    unsigned number = 0;
    const char* const begin = name.data() + prefix.size();
    const char* const end = name.data() + name.size();
    const auto [ptr, error] = std::from_chars(begin, end, number);
    if (error != std::errc{} || ptr != end) {
        return std::nullopt;
    }
    return number;
}

struct EventNode {
    unsigned number;
    fs::path path;
};

std::vector<EventNode> event_nodes(const fs::path& input_dir) {
    std::error_code error;
    fs::directory_iterator entries(input_dir, error);
    if (error) {
        throw DeviceError("evdev: cannot search " + input_dir.string() +
                          " for a force-feedback device: " + error.message());
    }
    std::vector<EventNode> nodes;
    for (const auto& entry : entries) {
        if (auto number = event_number(entry.path().filename().string())) {
            nodes.push_back({*number, entry.path()});
        }
    }
    // event2 before event10: the kernel numbers devices in the order they appeared.
    std::sort(nodes.begin(), nodes.end(),
              [](const EventNode& a, const EventNode& b) { return a.number < b.number; });
    return nodes;
}

bool udev_tags_vibra(const fs::path& udev_data, const CharDeviceNumber& number) {
    std::ifstream entry(udev_data /
                        ("c" + std::to_string(number.major) + ":" + std::to_string(number.minor)));
    for (std::string line; std::getline(entry, line);) {
        if (line == "E:FEEDBACKD_TYPE=vibra") {
            return true;
        }
    }
    return false;
}

FfProbeResult kernel_force_feedback(const fs::path& path) {
    std::optional<EvdevNode> node;
    try {
        node.emplace(path, O_RDONLY | O_NONBLOCK);
    } catch (const EvdevOpenError& error) {
        return error.step() == EvdevOpenError::Step::open ? FfProbeResult::unreadable
                                                          : FfProbeResult::no_force_feedback;
    }
    const auto has = [&node](unsigned code) {
        return libevdev_has_event_code(node->device(), EV_FF, code) != 0;
    };
    const bool usable = has(FF_RUMBLE) || (has(FF_PERIODIC) && (has(FF_SINE) || has(FF_SQUARE)));
    const char* phys = libevdev_get_phys(node->device());
    const bool ours = phys != nullptr && std::string_view(phys) == kVirtualVibraPhys;
    return usable && !ours ? FfProbeResult::force_feedback : FfProbeResult::no_force_feedback;
}

std::optional<CharDeviceNumber> kernel_device_number(const fs::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0 || !S_ISCHR(status.st_mode)) {
        return std::nullopt;
    }
    return CharDeviceNumber{::major(status.st_rdev), ::minor(status.st_rdev)};
}

}  // namespace

DiscoveryProbe kernel_discovery_probe() {
    return {kernel_force_feedback, kernel_device_number};
}

DiscoveredDevice discover_ff_device(const DiscoverySettings& settings,
                                    const DiscoveryProbe& probe) {
    const auto nodes = event_nodes(settings.input_dir);
    std::optional<fs::path> first_with_ff;
    std::size_t unreadable = 0;
    for (const auto& node : nodes) {
        const FfProbeResult result = probe.force_feedback(node.path);
        if (result == FfProbeResult::unreadable) {
            ++unreadable;
        }
        if (result != FfProbeResult::force_feedback) {
            continue;
        }
        const auto number = probe.device_number(node.path);
        if (number && udev_tags_vibra(settings.udev_data, *number)) {
            return {node.path, true};
        }
        if (!first_with_ff) {
            first_with_ff = node.path;
        }
    }
    if (first_with_ff) {
        return {*first_with_ff, false};
    }
    std::string found = std::to_string(nodes.size()) + " event device" +
                        (nodes.size() == 1 ? "" : "s") + ", none with force feedback";
    if (unreadable > 0) {
        found += "; " + std::to_string(unreadable) + " could not be opened (permissions?)";
    }
    throw DeviceError("evdev: no force-feedback device in " + settings.input_dir.string() + " (" +
                      found + ")");
}

}  // namespace vibscore::drivers
