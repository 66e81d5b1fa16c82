#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

struct DriverInfo {
    std::string name;
    std::string description;
};

// The backends this build can create, for --list-drivers and error messages.
std::vector<DriverInfo> available_drivers();

// Creates backend `name` from its configuration section. Throws std::invalid_argument naming an
// unknown driver or a bad setting, DeviceError when its device cannot be opened.
std::unique_ptr<Actuator> make_actuator(const std::string& name,
                                        const std::map<std::string, std::string>& settings);

}  // namespace vibscore::drivers
