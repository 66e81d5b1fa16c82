#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "daemon/actuator/declaration.hpp"
#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

struct DriverInfo {
    std::string name;
    std::string description;
};

// The backends this build can create, then the driver modules in `drivers_dir`
// (include/vibscore/driver.h), for --list-drivers and error messages.
std::vector<DriverInfo> available_drivers(const std::filesystem::path& drivers_dir = {});

// Creates backend `name` from its configuration section: a built-in one, or else a driver
// module from `drivers_dir`. The common settings (max-on-time-ms, pulse-period-ms) are taken
// here. Throws std::invalid_argument naming an unknown driver or a bad setting, DeviceError
// when its device cannot be opened. `declared` is the actuator [actuator] declares, which the sim
// backend simulates.
std::unique_ptr<Actuator> make_actuator(
    const std::string& name, const std::map<std::string, std::string>& settings,
    const std::filesystem::path& drivers_dir = {},
    const std::optional<actuator::Declaration>& declared = std::nullopt);

}  // namespace vibscore::drivers
