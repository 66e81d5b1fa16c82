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
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"
#include "daemon/actuator_config.hpp"

namespace vibscore::daemon {

namespace {

const std::vector<std::string> kDaemonKeys = {
    "driver",        "drivers-dir",         "store",         "shipped",
    "separation-ms", "requests-per-second", "request-burst", "rt-priority"};

std::string trim(const std::string& text) {
    const auto begin = text.find_first_not_of(" \t\r");
    if (begin == std::string::npos) {
        return {};
    }
    return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

double positive_number(const std::string& value, const std::string& where, const std::string& key,
                       double max) {
    double number = 0.0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
    if (error != std::errc() || end != value.data() + value.size() || !std::isfinite(number) ||
        !above_zero(number) || number > max) {
        throw ConfigError(where + ": " + shown_text(key) + " = " + quoted_text(value) +
                          " is not a number above 0 and at most " + number_text(max) +
                          " (the smallest above 0 is " + number_text(kSmallestAboveZero) + ")");
    }
    return number;
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

namespace {

// Where a comment begins: '#' or ';' at the start of a line or after a blank, as the shipped
// file and the docs write them ("carrier-hz = 20000  # erm only"). npos: no comment.
std::size_t comment_start(const std::string& line) {
    for (std::size_t i = 0; i < line.size(); ++i) {
        if ((line[i] == '#' || line[i] == ';') &&
            (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t' || line[i - 1] == '\r')) {
            return i;
        }
    }
    return std::string::npos;
}

// A second "key = value" for a key the section already set is a mistake (which one was meant?),
// not a silent override.
void refuse_repeated(std::map<std::string, std::string>& lines, const std::string& section,
                     const std::string& key, const std::string& value, const std::string& where,
                     std::map<std::string, std::string>& values) {
    if (const auto first = lines.find(key); first != lines.end()) {
        throw ConfigError(where + ": " + shown_text(key) + " = " + quoted_text(value) + " sets " +
                          "[" + shown_text(section) + "] " + shown_text(key) + " again (" +
                          first->second + " set it to " + quoted_text(values[key]) +
                          "); keep one of them");
    }
    lines[key] = where;
    values[key] = value;
}

}  // namespace

DaemonConfig parse_config(const std::string& text, const std::string& file, DaemonConfig config) {
    std::istringstream lines(text);
    std::string line;
    std::string section;
    int number = 0;
    bool fit_auto = false;  // [clefs] fit = auto
    std::string fit_where;
    // Every value as the file gave it, by section and key, for the messages about repeated keys.
    std::map<std::string, std::map<std::string, std::string>> values;
    while (std::getline(lines, line)) {
        ++number;
        const std::string where = file + ":" + std::to_string(number);
        const auto content = trim(line.substr(0, comment_start(line)));
        if (content.empty()) {
            continue;
        }
        if (const auto mark = content.find_first_of("#;"); mark != std::string::npos) {
            // "store = /var/lib/vib#score": cutting it at the '#' would quietly use another path.
            const auto equals = content.find('=');
            const std::string what = equals == std::string::npos || content.front() == '['
                                         ? quoted_text(content)
                                         : shown_text(trim(content.substr(0, equals))) + " = " +
                                               quoted_text(trim(content.substr(equals + 1)));
            throw ConfigError(where + ": " + what + " holds '" + content[mark] +
                              "', which starts a comment only at the start of a line or after a "
                              "space; a value cannot contain it");
        }
        if (content.front() == '[') {
            if (content.back() != ']' || content.size() < 3) {
                throw ConfigError(where + ": malformed section header " + quoted_text(content));
            }
            section = trim(content.substr(1, content.size() - 2));
            if (section != "daemon") {
                config.driver_settings[section];  // an empty section still names a driver
                config.section_lines.try_emplace(section, where);
            }
            continue;
        }
        const auto equals = content.find('=');
        if (equals == std::string::npos) {
            throw ConfigError(where + ": expected \"key = value\", found " + quoted_text(content));
        }
        const auto key = trim(content.substr(0, equals));
        const auto value = trim(content.substr(equals + 1));
        if (section.empty()) {
            throw ConfigError(where + ": " + quoted_text(key) + " is outside any [section]");
        }
        refuse_repeated(config.setting_lines[section], section, key, value, where, values[section]);
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
                config.limits.set(key, value);
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
    config.actuator = declared_actuator(config);
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
