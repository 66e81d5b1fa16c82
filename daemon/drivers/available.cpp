#include "daemon/drivers/available.hpp"

#include <stdexcept>

#include "daemon/drivers/evdev_actuator.hpp"
#include "daemon/drivers/sim_actuator.hpp"

namespace vibscore::drivers {

std::vector<DriverInfo> available_drivers() {
    return {
        {"sim", "simulated ERM or LRA: models the response, traces commands, shows a meter"},
        {"evdev", "Linux force feedback (a vibra, rumble motors): periodic or rumble effects"},
    };
}

std::unique_ptr<Actuator> make_actuator(const std::string& name,
                                        const std::map<std::string, std::string>& settings) {
    if (name == "sim") {
        return make_sim_actuator(settings);
    }
    if (name == "evdev") {
        return make_evdev_actuator(settings);
    }
    std::string known;
    for (const auto& driver : available_drivers()) {
        known += (known.empty() ? "" : ", ") + driver.name;
    }
    throw std::invalid_argument("unknown driver \"" + name + "\" (available: " + known + ")");
}

}  // namespace vibscore::drivers
