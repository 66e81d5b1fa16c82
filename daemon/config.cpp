#include "daemon/config.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/above_zero.hpp"
#include "common/closest_name.hpp"
#include "common/ini_reader.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"

namespace vibscore::daemon {

namespace {

const std::vector<std::string> kDaemonKeys = {
    "driver",        "drivers-dir",         "store",         "shipped",
    "separation-ms", "requests-per-second", "request-burst", "rt-priority"};

double positive_number(const std::string& value, const std::string& where, const std::string& key,
                       double max) {
    const auto number = ini_number(value);
    if (!number || !above_zero(*number) || *number > max) {
        throw ConfigError(where + ": " + shown_text(key) + " = " + quoted_text(value) +
                          " is not a number above 0 and at most " + number_text(max) +
                          " (the smallest above 0 is " + number_text(kSmallestAboveZero) + ")");
    }
    return *number;
}

int priority(const std::string& value, const std::string& where, const std::string& key) {
    int number = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
    if (error != std::errc() || end != value.data() + value.size() || number < 0 || number > 99) {
        throw ConfigError(where + ": " + shown_text(key) + " = " + quoted_text(value) +
                          " is not a whole number from 0 to 99");
    }
    return number;
}

// One line of [clefs]: both sides are registry clef names, the left one may be "*".
void add_device_clef(DeviceClefs& clefs, const std::string& written, const std::string& device,
                     const std::string& where) {
    if (!is_valid_name(device)) {
        throw ConfigError(where + ": [clefs] " + shown_text(written) + " = " + quoted_text(device) +
                          " is not a registry clef name (a-z 0-9 . _ -)");
    }
    if (written == "*") {
        clefs.otherwise = device;
    } else if (is_valid_name(written)) {
        clefs.by_written[written] = device;
    } else {
        throw ConfigError(where + ": [clefs] " + quoted_text(written) +
                          " is neither a registry clef name nor \"*\"");
    }
}

// [clefs] fit = auto | off.
bool fit_mode(const std::string& value, const std::string& where) {
    if (value == "auto" || value == "off") {
        return value == "auto";
    }
    throw ConfigError(where + ": [clefs] fit = " + quoted_text(value) + " is neither auto nor off");
}

}  // namespace

const std::map<std::string, std::string>& DaemonConfig::settings_of(const std::string& name) const {
    static const std::map<std::string, std::string> kNone;
    const auto found = driver_settings.find(name);
    return found == driver_settings.end() ? kNone : found->second;
}

std::string DaemonConfig::where(const std::string& driver, const std::string& key) const {
    if (const auto section = setting_lines.find(driver); section != setting_lines.end()) {
        if (const auto line = section->second.find(key); line != section->second.end()) {
            return line->second + ": ";
        }
    }
    const auto header = section_lines.find(driver);
    return header == section_lines.end() ? std::string() : header->second + ": ";
}

std::vector<std::string> unknown_sections(const DaemonConfig& config,
                                          const std::vector<std::string>& known) {
    std::vector<std::string> warnings;
    for (const auto& [section, where] : config.section_lines) {
        std::vector<std::string> candidates(known);
        candidates.push_back("daemon");
        candidates.insert(candidates.end(), std::begin(kServiceSections),
                          std::end(kServiceSections));
        if (std::find(candidates.begin(), candidates.end(), section) != candidates.end()) {
            continue;
        }
        const auto meant = closest_name(section, candidates);
        warnings.push_back(where + ": unknown section " + "[" + shown_text(section) + "]" +
                           ": no driver of that name, so its keys apply nowhere" +
                           (meant ? " (did you mean [" + *meant + "]?)" : ""));
    }
    return warnings;
}

DaemonConfig parse_config(const std::string& text, const std::string& file, DaemonConfig config) {
    std::vector<IniLine> lines;
    try {
        lines = read_ini(text, file);
    } catch (const IniError& error) {
        throw ConfigError(error.what());
    }
    bool fit_auto = false;  // [clefs] fit = auto
    std::string fit_where;
    for (const IniLine& line : lines) {
        const std::string& section = line.section;
        const std::string& where = line.where;
        if (line.is_header()) {
            if (section != "daemon") {
                config.driver_settings[section];  // an empty section still names a driver
                config.section_lines.try_emplace(section, where);
            }
            continue;
        }
        const std::string& key = line.key;
        const std::string& value = line.value;
        config.setting_lines[section][key] = where;
        if (section == "clefs") {
            if (key == "fit") {
                fit_where = where;
                fit_auto = fit_mode(value, where);
            } else {
                add_device_clef(config.device_clefs, key, value, where);
            }
            continue;
        }
        if (section == kLimitsSection) {
            try {
                if (!config.admission.set(key, value)) {
                    config.limits.set(key, value);
                }
            } catch (const std::invalid_argument& error) {
                throw ConfigError(where + ": " + error.what());
            }
            continue;
        }
        if (section != "daemon") {
            config.driver_settings[section][key] = value;
            continue;
        }
        if (key == "driver") {
            config.driver = value;
        } else if (key == "store") {
            config.store = value;
        } else if (key == "shipped") {
            config.shipped = value;
        } else if (key == "drivers-dir") {
            config.drivers_dir = value;
        } else if (key == "separation-ms") {
            config.separation_ms = positive_number(value, where, key, 1000.0);
        } else if (key == "requests-per-second") {
            config.requests_per_second = positive_number(value, where, key, 1e6);
        } else if (key == "request-burst") {
            config.request_burst = positive_number(value, where, key, 1e6);
            if (config.request_burst < 1.0) {
                // A bucket that never holds a whole token refuses every request.
                throw ConfigError(where + ": request-burst = " + quoted_text(value) +
                                  " is below 1: the burst must let at least one request through");
            }
        } else if (key == "rt-priority") {
            config.rt_priority = priority(value, where, key);
        } else {
            const auto meant = closest_name(key, kDaemonKeys);
            throw ConfigError(where + ": unknown key " + quoted_text(key) + " in [daemon]" +
                              (meant ? " (did you mean " + *meant + "?)" : "") +
                              " (expected driver, drivers-dir, store, shipped, separation-ms, "
                              "requests-per-second, request-burst or rt-priority)");
        }
        if (value.empty()) {
            throw ConfigError(where + ": " + shown_text(key) + " has no value");
        }
    }
    try {
        if (const auto declared = actuator::find_section(lines)) {
            config.actuator = actuator::parse_declaration(declared->settings, declared->where);
        } else {
            config.actuator.reset();
        }
    } catch (const actuator::DeclarationError& error) {
        throw ConfigError(error.what());
    }
    config.device_clefs.fit_to.reset();
    if (fit_auto) {
        if (!config.actuator) {
            throw ConfigError(fit_where +
                              ": [clefs] fit = auto needs an [actuator] section to fit to");
        }
        config.device_clefs.fit_to = config.actuator;
    }
    return config;
}

DaemonConfig load_config(const std::filesystem::path& path, DaemonConfig defaults) {
    // A directory opens as a stream that reads nothing: without this, the built-in defaults
    // would quietly apply (and create the default store).
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        throw ConfigError(path.string() + ": is a directory, not a configuration file");
    }
    std::ifstream in(path);
    if (!in) {
        throw ConfigError(path.string() + ": cannot open: " + std::strerror(errno));
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) {
        throw ConfigError(path.string() + ": cannot read: " + std::strerror(errno));
    }
    return parse_config(text.str(), path.string(), std::move(defaults));
}

std::vector<std::string> missing_device_clefs(const DaemonConfig& config,
                                              const Registry& registry) {
    std::vector<std::string> warnings;
    const auto lines = config.setting_lines.find("clefs");
    const auto check = [&](const std::string& written, const std::string& device) {
        if (registry.contains(DocumentKind::clef, device)) {
            return;
        }
        std::string where;
        if (lines != config.setting_lines.end()) {
            if (const auto line = lines->second.find(written); line != lines->second.end()) {
                where = line->second + ": ";
            }
        }
        warnings.push_back(where + "[clefs] " + shown_text(written) + " = " + quoted_text(device) +
                           ": the registry has no clef " + quoted_text(device) +
                           ", so Play refuses every score this maps until one is composed");
    };
    for (const auto& [written, device] : config.device_clefs.by_written) {
        check(written, device);
    }
    if (!config.device_clefs.otherwise.empty()) {
        check("*", config.device_clefs.otherwise);
    }
    return warnings;
}

}  // namespace vibscore::daemon
