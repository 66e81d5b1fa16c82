#include "daemon/actuator_host.hpp"

#include <exception>
#include <utility>

#include "daemon/drivers/disconnected_actuator.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "daemon/log.hpp"

namespace vibscore::daemon {

ActuatorHost::ActuatorHost(const DaemonConfig& config)
    : config_(config), drivers_dir_(config.drivers_dir), configured_(config.driver) {
    auto opened = open_naming(config.driver, configured_reason());
    driver_ = opened.driver;
    settings_ = config.settings_of(opened.driver);
    auto_fell_back_ = opened.fell_back;
    reason_ = opened.reason;
    actuator_ = std::move(opened.actuator);
}

std::string ActuatorHost::configured_reason() const {
    const std::string where = config_.where("daemon", "driver");  // "file:line: " or ""
    return (where.empty() ? "configured: " : "configured at " + where) +
           "driver = " + config_.driver;
}

drivers::AutoChoice ActuatorHost::open_naming(const std::string& driver,
                                              const std::string& reason) const {
    const auto open_configured = [this](const std::string& name) {
        return open(name, config_.settings_of(name), config_.drivers_dir);
    };
    if (driver != drivers::kAutoDriver) {
        return {driver, reason, false, open_configured(driver)};
    }
    // "file:line: " as "file:line" (or "" when the settings came from no file).
    const auto at = [this](const std::string& section, const std::string& key) {
        const std::string where = config_.where(section, key);
        return where.substr(0, where.rfind(": "));
    };
    std::map<std::string, std::string> sections;
    for (const auto& [name, settings] : config_.driver_settings) {
        sections[name] = at(name, "");
    }
    auto choice = drivers::choose_driver(drivers::auto_search(
        at("daemon", "driver"), sections, config_.settings_of("evdev"), open_configured));
    if (choice.fell_back) {
        log::warning(choice.reason);
    } else {
        log::info(choice.reason);
    }
    return choice;
}

std::unique_ptr<drivers::Actuator> ActuatorHost::open(
    const std::string& driver, const DriverSettingsMap& settings,
    const std::filesystem::path& drivers_dir) const {
    try {
        return drivers::make_actuator(driver, settings, drivers_dir);
    } catch (const drivers::SettingError& error) {
        throw drivers::SettingError(error.key(), config_.where(driver, error.key()) + error.what());
    }
}

std::vector<drivers::DriverInfo> ActuatorHost::drivers() const {
    return drivers::available_drivers(config_.drivers_dir);
}

void ActuatorHost::switch_to(const std::string& driver) {
    switch_running(
        driver,
        "switched at run time (SwitchDriver, vibscore driver " + driver +
            "); a reload or a restart returns to the configuration's driver = " + config_.driver,
        false);
}

void ActuatorHost::switch_running(const std::string& driver, const std::string& reason,
                                  bool follows_config) {
    try {
        open_in_place_of_running(driver, reason, follows_config);
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

void ActuatorHost::open_in_place_of_running(const std::string& driver, const std::string& reason,
                                            bool follows_config) {
    const std::filesystem::path drivers_dir = config_.drivers_dir;
    // The player must never point at a closed backend, not even for a moment.
    drivers::DisconnectedActuator switching("switching to driver " + driver);
    if (player_) {
        player_->stop_all("driver-switch");
        player_->replace_actuator(switching);
    }
    actuator_.reset();
    drivers::AutoChoice opened;
    try {
        opened = open_naming(driver, reason);
    } catch (const std::exception& error) {
        log::error("driver " + driver + " failed to open (" + error.what() + "); reopening " +
                   driver_);
        follows_config_ = false;  // a reload tries the configuration's driver again
        try {
            actuator_ = open(driver_, settings_, drivers_dir_);
        } catch (const std::exception& reopen_error) {
            actuator_ = std::make_unique<drivers::DisconnectedActuator>(
                "driver " + driver + " failed (" + error.what() + ") and driver " + driver_ +
                " would not reopen (" + reopen_error.what() + ")");
            driver_ = "none";
            settings_.clear();
            reason_ = "driver " + driver + " failed to open (" + error.what() +
                      ") and the one before would not reopen (" + reopen_error.what() + ")";
            log::error(std::string("no actuator until the next switch or reload: ") +
                       reopen_error.what());
        }
        if (player_) {
            player_->replace_actuator(*actuator_);
        }
        throw;
    }
    actuator_ = std::move(opened.actuator);
    if (player_) {
        player_->replace_actuator(*actuator_);
    }
    driver_ = opened.driver;
    settings_ = config_.settings_of(opened.driver);
    drivers_dir_ = drivers_dir;
    reason_ = opened.reason;
    auto_fell_back_ = opened.fell_back;
    follows_config_ = follows_config;
    if (follows_config) {
        configured_ = config_.driver;
    }
    log::info("driver is now " + driver_);
}

bool ActuatorHost::follow_config() {
    const bool differs = config_.driver != configured_ || !follows_config_ ||
                         (config_.driver == drivers::kAutoDriver && auto_fell_back_) ||
                         config_.settings_of(driver_) != settings_ ||
                         config_.drivers_dir != drivers_dir_;
    if (differs) {
        switch_running(config_.driver, configured_reason(), true);
    }
    return differs;
}

}  // namespace vibscore::daemon
