#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "daemon/registry/registry.hpp"
#include "score/bundle.hpp"

// Device clefs (thesis §4.4): a score names the clefs it was written for, and the integrator maps
// them onto clefs tuned for this device's actuator in vibscored.conf's [clefs] section, e.g.
// "lra-phone = my-board-erm" and "* = my-board-erm" for any other clef.
namespace vibscore::daemon {

struct DeviceClefs {
    std::map<std::string, std::string, std::less<>> by_written;  // written clef -> device clef
    std::string otherwise;  // "*": the device clef for any other; empty: those play as written

    // The registry clef a bar written for `written` plays through on this device.
    std::string for_written(std::string_view written) const;
    bool empty() const { return by_written.empty() && otherwise.empty(); }
    bool operator==(const DeviceClefs&) const = default;
};

// "lra-phone -> my-board-erm, * -> my-board-default", or "none" (every clef plays as written).
std::string describe(const DeviceClefs& clefs);

// A bar's clef as the score names it, and the one it plays through here.
struct BarClef {
    std::string written;
    std::string device;
    bool operator==(const BarClef&) const = default;
};

// Every bar of a score bound to the registry clefs it names, in order.
std::vector<BarClef> bar_clefs(const ScoreBundle& written, const DeviceClefs& clefs);

// The score bound again, each declared clef replaced by its device clef, except the clefs the
// caller sent along with it (`sent`, by href: the caller's choice, as an override is). Throws
// RegistryError (not_found) naming the mapping when a device clef is not in the registry,
// DocumentError when the score's notes do not fit a device clef (a string or number it lacks).
ScoreBundle bind_device_clefs(const Registry& registry, const ScoreBundle& written,
                              const DeviceClefs& clefs,
                              const std::map<std::string, std::string>& sent = {});

}  // namespace vibscore::daemon
