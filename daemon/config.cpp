#include "daemon/config.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace vibscore::daemon {

namespace {

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
        number <= 0.0 || number > max) {
        throw ConfigError(where + ": " + key + " = \"" + value +
                          "\" is not a number above 0 and at most " + std::to_string(max));
    }
    return number;
}

// One line of [clefs]: both sides are registry clef names, the left one may be "*".
void add_device_clef(DeviceClefs& clefs, const std::string& written, const std::string& device,
                     const std::string& where) {
    if (!is_valid_name(device)) {
        throw ConfigError(where + ": [clefs] " + written + " = \"" + device +
                          "\" is not a registry clef name (a-z 0-9 . _ -)");
    }
    if (written == "*") {
        clefs.otherwise = device;
    } else if (is_valid_name(written)) {
        clefs.by_written[written] = device;
    } else {
        throw ConfigError(where + ": [clefs] \"" + written +
                          "\" is neither a registry clef name nor \"*\"");
    }
}

}  // namespace

const std::map<std::string, std::string>& DaemonConfig::settings_of(const std::string& name) const {
    static const std::map<std::string, std::string> kNone;
    const auto found = driver_settings.find(name);
    return found == driver_settings.end() ? kNone : found->second;
}

DaemonConfig parse_config(const std::string& text, const std::string& file, DaemonConfig config) {
    std::istringstream lines(text);
    std::string line;
    std::string section;
    int number = 0;
    while (std::getline(lines, line)) {
        ++number;
        const std::string where = file + ":" + std::to_string(number);
        const auto content = trim(line.substr(0, line.find_first_of("#;")));
        if (content.empty()) {
            continue;
        }
        if (content.front() == '[') {
            if (content.back() != ']' || content.size() < 3) {
                throw ConfigError(where + ": malformed section header \"" + content + "\"");
            }
            section = trim(content.substr(1, content.size() - 2));
            continue;
        }
        const auto equals = content.find('=');
        if (equals == std::string::npos) {
            throw ConfigError(where + ": expected \"key = value\", found \"" + content + "\"");
        }
        const auto key = trim(content.substr(0, equals));
        const auto value = trim(content.substr(equals + 1));
        if (section.empty()) {
            throw ConfigError(where + ": \"" + key + "\" is outside any [section]");
        }
        if (section == "clefs") {
            add_device_clef(config.device_clefs, key, value, where);
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
        } else {
            throw ConfigError(where + ": unknown key \"" + key +
                              "\" in [daemon] (expected driver, drivers-dir, store, shipped, "
                              "separation-ms, requests-per-second or request-burst)");
        }
        if (value.empty()) {
            throw ConfigError(where + ": " + key + " has no value");
        }
    }
    return config;
}

DaemonConfig load_config(const std::filesystem::path& path, DaemonConfig defaults) {
    std::ifstream in(path);
    if (!in) {
        throw ConfigError(path.string() + ": cannot open");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parse_config(text.str(), path.string(), std::move(defaults));
}

}  // namespace vibscore::daemon
