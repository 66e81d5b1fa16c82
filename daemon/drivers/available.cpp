#include "daemon/drivers/available.hpp"

#include <stdexcept>

#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/drivers/sim_actuator.hpp"

namespace vibscore::drivers {

std::vector<DriverInfo> available_drivers() {
    return {
        {"sim", "simulated ERM or LRA: models the response, traces commands, shows a meter"},
    };
}

namespace {

std::unique_ptr<Actuator> make_backend(const std::string& name,
                                       const std::map<std::string, std::string>& settings) {
    if (name == "sim") {
        return make_sim_actuator(settings);
    }
    return nullptr;
}

}  // namespace

std::unique_ptr<Actuator> make_actuator(const std::string& name,
                                        const std::map<std::string, std::string>& settings) {
    auto own_settings = settings;
    const CommonSettings common = take_common_settings(name, own_settings);
    if (auto backend = make_backend(name, own_settings)) {
        return std::make_unique<ConfiguredActuator>(std::move(backend), common);
    }
    std::string known;
    for (const auto& driver : available_drivers()) {
        known += (known.empty() ? "" : ", ") + driver.name;
    }
    throw std::invalid_argument("unknown driver \"" + name + "\" (available: " + known + ")");
}

}  // namespace vibscore::drivers
