#include "daemon/drivers/available.hpp"

#include <stdexcept>

#include "daemon/drivers/gpio_pwm_actuator.hpp"
#include "daemon/drivers/led_vibrator_actuator.hpp"
#include "daemon/drivers/sim_actuator.hpp"
#include "daemon/drivers/sysfs_pwm_actuator.hpp"

namespace vibscore::drivers {

std::vector<DriverInfo> available_drivers() {
    return {
        {"sim", "simulated ERM or LRA: models the response, traces commands, shows a meter"},
        {"gpio-erm", "ERM on a GPIO line: software PWM from a real-time thread"},
        {"gpio-lra", "LRA on an H-bridge of two GPIO lines driven in antiphase"},
        {"sysfs-pwm", "ERM or LRA on a hardware PWM channel (/sys/class/pwm)"},
        {"led-vibrator", "on/off vibrator exposed as an LED with the transient trigger"},
        {"timed-output", "on/off vibrator through the Android timed_output interface"},
    };
}

std::unique_ptr<Actuator> make_actuator(const std::string& name,
                                        const std::map<std::string, std::string>& settings) {
    if (name == "sim") {
        return make_sim_actuator(settings);
    }
    if (name == "gpio-erm") {
        return make_gpio_erm_actuator(settings);
    }
    if (name == "gpio-lra") {
        return make_gpio_lra_actuator(settings);
    }
    if (name == "sysfs-pwm") {
        return make_sysfs_pwm_actuator(settings);
    }
    if (name == "led-vibrator") {
        return make_led_vibrator_actuator(settings);
    }
    if (name == "timed-output") {
        return make_timed_output_actuator(settings);
    }
    std::string known;
    for (const auto& driver : available_drivers()) {
        known += (known.empty() ? "" : ", ") + driver.name;
    }
    throw std::invalid_argument("unknown driver \"" + name + "\" (available: " + known + ")");
}

}  // namespace vibscore::drivers
