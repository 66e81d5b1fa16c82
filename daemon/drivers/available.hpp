#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/module_catalog.hpp"

namespace vibscore::drivers {

struct DriverInfo {
    std::string name;
    std::string description;
};

// The backends this build has in itself.
std::vector<std::string> built_in_driver_names();
bool is_built_in_driver(const std::string& name);

// The driver modules of `drivers_dir`, each tried out once (ModuleCatalog::scan), none of them
// taking a built-in driver's name.
std::shared_ptr<const ModuleCatalog> scan_driver_modules(const std::filesystem::path& drivers_dir);

// The backends this build can create, then the driver modules of `modules`, for
// --list-drivers, ListDrivers and error messages. Loads nothing.
std::vector<DriverInfo> available_drivers(const ModuleCatalog& modules);
// The same for the modules of `drivers_dir`, scanned now (a command line's one look).
std::vector<DriverInfo> available_drivers(const std::filesystem::path& drivers_dir = {});

// Creates backend `name` from its configuration section: a built-in one, or else a driver
// module of `modules`. The common settings (max-on-time-ms, pulse-period-ms) are taken here.
// Throws std::invalid_argument naming an unknown driver, a refused module and why, or a bad
// setting; DeviceError when its device cannot be opened. `declared` is the actuator [actuator]
// declares, which the sim backend simulates.
std::unique_ptr<Actuator> make_actuator(
    const std::string& name, const std::map<std::string, std::string>& settings,
    const ModuleCatalog& modules,
    const std::optional<actuator::Declaration>& declared = std::nullopt);
// The same with the modules of `drivers_dir`, scanned now.
std::unique_ptr<Actuator> make_actuator(
    const std::string& name, const std::map<std::string, std::string>& settings,
    const std::filesystem::path& drivers_dir = {},
    const std::optional<actuator::Declaration>& declared = std::nullopt);

}  // namespace vibscore::drivers
