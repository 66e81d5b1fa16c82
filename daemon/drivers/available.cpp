#include "daemon/drivers/available.hpp"

#include <algorithm>
#include <stdexcept>

#include "common/log.hpp"
#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/drivers/evdev_actuator.hpp"
#include "daemon/drivers/external_driver.hpp"
#include "daemon/drivers/gpio_pwm_actuator.hpp"
#include "daemon/drivers/led_vibrator_actuator.hpp"
#include "daemon/drivers/sim_actuator.hpp"
#include "daemon/drivers/sysfs_pwm_actuator.hpp"

namespace vibscore::drivers {

namespace {

std::vector<DriverInfo> built_in_drivers() {
    return {
        {"sim", "simulated ERM or LRA: models the response, traces commands, shows a meter"},
        {"evdev", "Linux force feedback (a vibra, rumble motors): periodic or rumble effects"},
        {"gpio-erm", "ERM on a GPIO line: software PWM from a real-time thread"},
        {"gpio-lra", "LRA on an H-bridge of two GPIO lines driven in antiphase"},
        {"sysfs-pwm", "ERM or LRA on a hardware PWM channel (/sys/class/pwm)"},
        {"led-vibrator", "on/off vibrator exposed as an LED with the transient trigger"},
        {"timed-output", "on/off vibrator through the Android timed_output interface"},
    };
}

}  // namespace

std::vector<std::string> built_in_driver_names() {
    std::vector<std::string> names;
    for (const auto& driver : built_in_drivers()) {
        names.push_back(driver.name);
    }
    return names;
}

bool is_built_in_driver(const std::string& name) {
    const auto built_in = built_in_drivers();
    return std::any_of(built_in.begin(), built_in.end(),
                       [&](const DriverInfo& driver) { return driver.name == name; });
}

std::shared_ptr<const ModuleCatalog> scan_driver_modules(const std::filesystem::path& drivers_dir) {
    return ModuleCatalog::scan(drivers_dir, built_in_driver_names());
}

std::vector<DriverInfo> available_drivers(const ModuleCatalog& modules) {
    auto drivers = built_in_drivers();
    for (const auto& module : modules.modules()) {
        drivers.push_back(
            {module.name, module.description + " (" + module.path.filename().string() + ")"});
    }
    return drivers;
}

std::vector<DriverInfo> available_drivers(const std::filesystem::path& drivers_dir) {
    return available_drivers(*scan_driver_modules(drivers_dir));
}

namespace {

std::unique_ptr<Actuator> make_backend(const std::string& name,
                                       const std::map<std::string, std::string>& settings,
                                       const std::optional<actuator::Declaration>& declared) {
    if (name == "sim") {
        return make_sim_actuator(settings, declared);
    }
    if (name == "evdev") {
        return make_evdev_actuator(settings);
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
    return nullptr;
}

}  // namespace

std::unique_ptr<Actuator> make_actuator(const std::string& name,
                                        const std::map<std::string, std::string>& settings,
                                        const ModuleCatalog& modules,
                                        const std::optional<actuator::Declaration>& declared) {
    auto own_settings = settings;
    const CommonSettings common = take_common_settings(name, own_settings);
    auto backend = is_built_in_driver(name) ? make_backend(name, own_settings, declared)
                                            : modules.open(name, own_settings);
    if (backend) {
        return std::make_unique<ConfiguredActuator>(std::move(backend), common);
    }
    if (const auto* refused = modules.refused_as(name)) {
        throw std::invalid_argument("driver \"" + name + "\": module " + refused->path.string() +
                                    " is not loaded: " + refused->reason);
    }
    std::string known;
    for (const auto& driver : available_drivers(modules)) {
        known += (known.empty() ? "" : ", ") + driver.name;
    }
    throw std::invalid_argument("unknown driver \"" + name + "\" (available: " + known + ")");
}

std::unique_ptr<Actuator> make_actuator(const std::string& name,
                                        const std::map<std::string, std::string>& settings,
                                        const std::filesystem::path& drivers_dir,
                                        const std::optional<actuator::Declaration>& declared) {
    return make_actuator(name, settings, *scan_driver_modules(drivers_dir), declared);
}

}  // namespace vibscore::drivers
