#include "daemon/actuator_host.hpp"

#include <exception>
#include <utility>

#include "daemon/drivers/disconnected_actuator.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "daemon/log.hpp"

namespace vibscore::daemon {

ActuatorHost::ActuatorHost(const DaemonConfig& config)
    : config_(config),
      driver_(config.driver),
      settings_(config.settings_of(config.driver)),
      drivers_dir_(config.drivers_dir),
      declared_(config.actuator),
      actuator_(open(driver_, settings_, drivers_dir_, declared_)) {
    if (declared_) {
        log::info("actuator: " + actuator::describe(*declared_));
    }
}

void ActuatorHost::attach(Player& player) {
    player_ = &player;
    player_->set_actuator(config_.actuator);
}

std::unique_ptr<drivers::Actuator> ActuatorHost::open(
    const std::string& driver, const DriverSettingsMap& settings,
    const std::filesystem::path& drivers_dir,
    const std::optional<actuator::Declaration>& declared) const {
    try {
        return drivers::make_actuator(driver, settings, drivers_dir, declared);
    } catch (const drivers::SettingError& error) {
        throw drivers::SettingError(error.key(), config_.where(driver, error.key()) + error.what());
    }
}

std::vector<drivers::DriverInfo> ActuatorHost::drivers() const {
    return drivers::available_drivers(config_.drivers_dir);
}

void ActuatorHost::switch_to(const std::string& driver) {
    try {
        open_in_place_of_running(driver);
    } catch (...) {
        if (changed_) {
            changed_();
        }
        throw;
    }
    if (changed_) {
        changed_();
    }
}

void ActuatorHost::open_in_place_of_running(const std::string& driver) {
    const DriverSettingsMap settings = config_.settings_of(driver);
    const std::filesystem::path drivers_dir = config_.drivers_dir;
    const std::optional<actuator::Declaration> declared = config_.actuator;
    // The player must never point at a closed backend, not even for a moment.
    drivers::DisconnectedActuator switching("switching to driver " + driver);
    if (player_) {
        player_->stop_all("driver-switch");
        player_->replace_actuator(switching);
    }
    actuator_.reset();
    try {
        actuator_ = open(driver, settings, drivers_dir, declared);
    } catch (const std::exception& error) {
        log::error("driver " + driver + " failed to open (" + error.what() + "); reopening " +
                   driver_);
        try {
            actuator_ = open(driver_, settings_, drivers_dir_, declared_);
        } catch (const std::exception& reopen_error) {
            actuator_ = std::make_unique<drivers::DisconnectedActuator>(
                "driver " + driver + " failed (" + error.what() + ") and driver " + driver_ +
                " would not reopen (" + reopen_error.what() + ")");
            driver_ = "none";
            settings_.clear();
            log::error(std::string("no actuator until the next switch or reload: ") +
                       reopen_error.what());
        }
        if (player_) {
            player_->replace_actuator(*actuator_);
        }
        throw;
    }
    if (player_) {
        player_->replace_actuator(*actuator_);
    }
    driver_ = driver;
    settings_ = settings;
    drivers_dir_ = drivers_dir;
    declared_ = declared;
    log::info("driver is now " + driver);
}

bool ActuatorHost::follow_config() {
    const bool declaration_changed = config_.actuator != declared_;
    if (declaration_changed) {
        log::info("actuator: " +
                  (config_.actuator ? actuator::describe(*config_.actuator) : "none declared"));
    }
    if (player_) {
        player_->set_actuator(config_.actuator);
    }
    // Only the sim is made of the declaration; a real backend drives whatever is on the board.
    const bool differs =
        config_.driver != driver_ || config_.settings_of(config_.driver) != settings_ ||
        config_.drivers_dir != drivers_dir_ || (declaration_changed && config_.driver == "sim");
    if (differs) {
        switch_to(config_.driver);
    } else {
        declared_ = config_.actuator;
        if (declaration_changed && changed_) {
            changed_();  // the bus announces the new declaration
        }
    }
    return differs;
}

}  // namespace vibscore::daemon
