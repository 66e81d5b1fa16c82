#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "actuator/declaration.hpp"
#include "daemon/clef_fit_cache.hpp"
#include "daemon/registry/registry.hpp"
#include "daemon/render/fitting/clef_fit.hpp"
#include "score/bundle.hpp"

// Device clefs (thesis §4.4): a score names the clefs it was written for, and the integrator maps
// them onto clefs tuned for this device's actuator in vibscored.conf's [clefs] section, e.g.
// "lra-phone = my-board-erm" and "* = my-board-erm" for any other clef. With "fit = auto" every
// clef no line maps is fitted to the declared [actuator] as a score is bound (docs/clefs.md).
namespace vibscore::daemon {

struct DeviceClefs {
    std::map<std::string, std::string, std::less<>> by_written;  // written clef -> device clef
    std::string otherwise;  // "*": the device clef for any other; empty: those play as written
    // fit = auto: the actuator the clefs no line maps are fitted to (render::fit_clef).
    std::optional<actuator::Declaration> fit_to;

    // Whether a line of [clefs] maps `written` (an explicit map wins over fitting).
    bool maps(std::string_view written) const {
        return by_written.contains(written) || !otherwise.empty();
    }
    bool fits(std::string_view written) const { return fit_to && !maps(written); }
    // The registry clef a bar written for `written` plays through on this device, or
    // "written (fitted)" for one fitted to the actuator.
    std::string for_written(std::string_view written) const;
    bool empty() const { return by_written.empty() && otherwise.empty() && !fit_to; }
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
// With fit = auto, each clef no line maps (the sent ones too: they are written clefs) is fitted to
// the actuator; one that cannot be fitted plays as written. With `cache`, each fit is looked up
// there first and kept there (clef_fit_cache.hpp).
ScoreBundle bind_device_clefs(const Registry& registry, const ScoreBundle& written,
                              const DeviceClefs& clefs,
                              const std::map<std::string, std::string>& sent = {},
                              ClefFitCache* cache = nullptr);

// The log of fitting (docs/clefs.md): what fitting each registry clef no line maps changed, and
// what its fitted clef still asks that the actuator cannot give (render::clef_warnings). At start
// and on reload; nothing without fit = auto.
void log_clef_fits(const Registry& registry, const DeviceClefs& clefs);

// The log for a clef just stored: its fit, or (not fitted) the check's warnings against the
// declared actuator, if any. Never throws: the clef is stored whatever its log says.
void log_stored_clef(const Registry& registry, const DeviceClefs& clefs,
                     const std::optional<actuator::Declaration>& actuator, const std::string& name);

}  // namespace vibscore::daemon
