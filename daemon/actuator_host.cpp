#include "daemon/actuator_host.hpp"

#include <exception>
#include <utility>

#include "daemon/drivers/available.hpp"
#include "daemon/drivers/disconnected_actuator.hpp"
#include "daemon/log.hpp"

namespace vibscore::daemon {

ActuatorHost::ActuatorHost(std::string driver, DriverSettingsMap settings,
                           std::filesystem::path drivers_dir)
    : driver_(std::move(driver)),
      settings_(std::move(settings)),
      drivers_dir_(std::move(drivers_dir)),
      actuator_(open(driver_, settings_)) {}

std::unique_ptr<drivers::Actuator> ActuatorHost::open(const std::string& driver,
                                                      const DriverSettingsMap& settings) const {
    return drivers::make_actuator(driver, settings, drivers_dir_);
}

void ActuatorHost::switch_to(Player& player, const std::string& driver,
                             const DriverSettingsMap& settings) {
    player.stop_all("driver-switch");
    // The player must never point at a closed backend, not even for a moment.
    drivers::DisconnectedActuator switching("switching to driver " + driver);
    player.replace_actuator(switching);
    actuator_.reset();
    try {
        actuator_ = open(driver, settings);
    } catch (const std::exception& error) {
        log::error("driver " + driver + " failed to open (" + error.what() + "); reopening " +
                   driver_);
        try {
            actuator_ = open(driver_, settings_);
        } catch (const std::exception& reopen_error) {
            actuator_ = std::make_unique<drivers::DisconnectedActuator>(
                "driver " + driver + " failed (" + error.what() + ") and driver " + driver_ +
                " would not reopen (" + reopen_error.what() + ")");
            driver_ = "none";
            settings_.clear();
            log::error(std::string("no actuator until the next switch or reload: ") +
                       reopen_error.what());
        }
        player.replace_actuator(*actuator_);
        throw;
    }
    player.replace_actuator(*actuator_);
    driver_ = driver;
    settings_ = settings;
    log::info("driver is now " + driver);
}

}  // namespace vibscore::daemon
