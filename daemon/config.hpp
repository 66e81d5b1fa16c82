#pragma once

#include "config.h"
#include "daemon/device_clefs.hpp"

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

namespace vibscore::daemon {

// vibscored.conf: INI sections of "key = value" lines; '#' and ';' start comments.
//   [daemon]  driver, drivers-dir, store, shipped, separation-ms, requests-per-second,
//   request-burst
//   [clefs]   WRITTEN = DEVICE: the clef bars written for WRITTEN play through on this device;
//             "* = DEVICE" for any other clef
//   [NAME]    the settings of driver NAME (e.g. [sim] model = erm), handed to that driver
// docs/daemon.md documents every key.
struct DaemonConfig {
    std::string driver = "sim";
    std::filesystem::path store = "/var/lib/vibscore";
    std::filesystem::path shipped;  // default: the installed clefs directory
    std::filesystem::path drivers_dir = VIBSCORE_DRIVERDIR;  // driver modules (*.so)
    double separation_ms = 30.0;
    double requests_per_second = 50.0;
    double request_burst = 100.0;
    std::map<std::string, std::map<std::string, std::string>> driver_settings;  // by driver
    DeviceClefs device_clefs;

    const std::map<std::string, std::string>& settings_of(const std::string& driver) const;
};

// The file is wrong; the message is "path:line: what", naming the key and value.
class ConfigError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

DaemonConfig parse_config(const std::string& text, const std::string& file,
                          DaemonConfig defaults = {});
DaemonConfig load_config(const std::filesystem::path& path, DaemonConfig defaults = {});

}  // namespace vibscore::daemon
