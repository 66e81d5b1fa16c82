#include "daemon/drivers/available.hpp"

#include <algorithm>
#include <stdexcept>

#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/drivers/evdev_actuator.hpp"
#include "daemon/drivers/external_driver.hpp"
#include "daemon/drivers/sim_actuator.hpp"
#include "daemon/log.hpp"

namespace vibscore::drivers {

namespace {

std::vector<DriverInfo> built_in_drivers() {
    return {
        {"sim", "simulated ERM or LRA: models the response, traces commands, shows a meter"},
        {"evdev", "Linux force feedback (a vibra, rumble motors): periodic or rumble effects"},
    };
}

bool is_built_in(const std::string& name) {
    const auto built_in = built_in_drivers();
    return std::any_of(built_in.begin(), built_in.end(),
                       [&](const DriverInfo& driver) { return driver.name == name; });
}

}  // namespace

std::vector<DriverInfo> available_drivers(const std::filesystem::path& drivers_dir) {
    auto drivers = built_in_drivers();
    for (const auto& external : find_external_drivers(drivers_dir)) {
        if (is_built_in(external.name)) {
            log::warning("driver module " + external.path.string() + " is ignored: \"" +
                         external.name + "\" is a built-in driver");
            continue;
        }
        drivers.push_back(
            {external.name, external.description + " (" + external.path.filename().string() + ")"});
    }
    return drivers;
}

namespace {

std::unique_ptr<Actuator> make_backend(const std::string& name,
                                       const std::map<std::string, std::string>& settings) {
    if (name == "sim") {
        return make_sim_actuator(settings);
    }
    if (name == "evdev") {
        return make_evdev_actuator(settings);
    }
    return nullptr;
}

}  // namespace

std::unique_ptr<Actuator> make_actuator(const std::string& name,
                                        const std::map<std::string, std::string>& settings,
                                        const std::filesystem::path& drivers_dir) {
    auto own_settings = settings;
    const CommonSettings common = take_common_settings(name, own_settings);
    auto backend = is_built_in(name) ? make_backend(name, own_settings)
                                     : make_external_actuator(drivers_dir, name, own_settings);
    if (backend) {
        return std::make_unique<ConfiguredActuator>(std::move(backend), common);
    }
    std::string known;
    for (const auto& driver : available_drivers(drivers_dir)) {
        known += (known.empty() ? "" : ", ") + driver.name;
    }
    throw std::invalid_argument("unknown driver \"" + name + "\" (available: " + known + ")");
}

}  // namespace vibscore::drivers
