#include "daemon/drivers/auto_driver.hpp"

#include <stdexcept>
#include <vector>

namespace vibscore::drivers {

namespace {

// "a", "a or b", "a, b or c".
std::string one_of(const std::vector<std::string>& items) {
    std::string text;
    for (std::size_t i = 0; i < items.size(); ++i) {
        text += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
    }
    return text;
}

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items) {
        text += (text.empty() ? "" : "; ") + item;
    }
    return text;
}

}  // namespace

AutoChoice choose_driver(const AutoSearch& search) {
    const std::string head =
        std::string("driver = auto") + (search.where.empty() ? "" : " (" + search.where + ")");
    std::vector<std::string> searched;  // what was looked at and found wanting, in order
    const auto try_open = [&](const std::string& driver,
                              const std::string& found) -> std::optional<AutoChoice> {
        try {
            auto actuator = search.open(driver);
            std::string reason = head + ": " + found;
            if (!searched.empty()) {
                reason += " (before it: " + joined(searched) + ")";
            }
            return AutoChoice{driver, reason, false, std::move(actuator)};
        } catch (const std::invalid_argument&) {
            throw;  // the configuration is wrong: said as for a driver named outright
        } catch (const std::exception& error) {
            searched.push_back(error.what());
            return std::nullopt;
        }
    };

    if (search.evdev_device) {
        if (auto chosen = try_open(
                "evdev", "evdev on " + *search.evdev_device + ", the device [evdev] names")) {
            return std::move(*chosen);
        }
    } else {
        std::optional<DiscoveredDevice> found;
        try {
            found = search.discover();
        } catch (const std::exception& error) {
            searched.push_back(error.what());
        }
        if (found) {
            const std::string which =
                found->tagged_vibra
                    ? ", the force-feedback device udev tags FEEDBACKD_TYPE=vibra"
                    : ", the first force-feedback device (udev tags none FEEDBACKD_TYPE=vibra)";
            if (auto chosen = try_open("evdev", "evdev on " + found->path.string() + which)) {
                return std::move(*chosen);
            }
        }
    }

    std::vector<std::string> absent;
    for (const std::string driver : kAutoConfiguredDrivers) {
        const auto section = search.sections.find(driver);
        if (section == search.sections.end()) {
            absent.push_back("[" + driver + "]");
            continue;
        }
        const std::string named =
            "[" + driver + "]" + (section->second.empty() ? "" : " (" + section->second + ")");
        const auto before = searched.size();
        if (auto chosen = try_open(driver, driver + " on the device " + named + " configures")) {
            return std::move(*chosen);
        }
        searched[before] = named + ": " + searched[before];
    }

    AutoChoice fallback{"sim", "", true, search.open("sim")};
    fallback.reason =
        head +
        " found no actuator, so driver sim plays (nothing vibrates). Searched: " + joined(searched);
    if (!absent.empty()) {
        fallback.reason += std::string(searched.empty() ? "" : "; ") + "no " + one_of(absent) +
                           " section is configured";
    }
    fallback.reason +=
        ". To drive yours: a vibra's input device needs udev's FEEDBACKD_TYPE=vibra "
        "(docs/daemon.md, "
        "Device access); any other actuator, driver = NAME and its [NAME] section in "
        "vibscored.conf (vibscored --list-drivers; docs/drivers.md)";
    return fallback;
}

AutoSearch auto_search(std::string where, std::map<std::string, std::string> sections,
                       const std::map<std::string, std::string>& evdev_settings,
                       std::function<std::unique_ptr<Actuator>(const std::string&)> open) {
    // The keys of [evdev] that say where discovery looks (evdev_actuator.cpp reads them alike;
    // a bad value there is reported when the evdev backend opens).
    const auto setting = [&](const char* key) -> std::optional<std::string> {
        const auto found = evdev_settings.find(key);
        return found == evdev_settings.end() ? std::nullopt : std::optional(found->second);
    };
    DiscoverySettings discovery;
    discovery.input_dir = setting("input-dir").value_or(discovery.input_dir.string());
    discovery.udev_data = setting("udev-data").value_or(discovery.udev_data.string());
    AutoSearch search;
    search.where = std::move(where);
    search.sections = std::move(sections);
    search.evdev_device = setting("device");
    search.discover = [discovery] {
        return discover_ff_device(discovery, kernel_discovery_probe());
    };
    search.open = std::move(open);
    return search;
}

}  // namespace vibscore::drivers
