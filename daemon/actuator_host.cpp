#include "daemon/actuator_host.hpp"

#include <exception>
#include <stdexcept>
#include <utility>

#include "common/log.hpp"
#include "daemon/drivers/disconnected_actuator.hpp"
#include "daemon/drivers/driver_settings.hpp"

namespace vibscore::daemon {

namespace {

std::shared_ptr<const drivers::ModuleCatalog> modules_of(const DaemonConfig& config) {
    return config.modules ? config.modules : std::make_shared<const drivers::ModuleCatalog>();
}

}  // namespace

ActuatorHost::ActuatorHost(const DaemonConfig& config)
    : config_(config),
      driver_(config.driver),
      running_modules_(modules_of(config)),
      declared_(config.actuator),
      configured_(config.driver),
      modules_(running_modules_) {
    const auto crashed = read_module_record(config.module_record);
    remove_module_record(config.module_record);  // about the run that ended; this one starts afresh
    if (crashed && crashed->name != driver_) {
        log::warning("vibscored last ended while driver module " + crashed->name + " (" +
                     crashed->path.string() + ") was in use, without closing it");
    }
    std::string reason = configured_reason();
    if (const std::string refused = reason_to_run_sim_instead(crashed); !refused.empty()) {
        log::error(refused +
                   "; running driver sim instead, so the daemon serves. `vibscore driver " +
                   driver_ + "` or a reload tries it again");
        reason = refused + "; driver sim runs instead until a reload or `vibscore driver " +
                 driver_ + "`";
        driver_ = "sim";
        follows_config_ = false;  // a reload tries the configured module again
    }
    try {
        auto opened = open_naming(driver_, reason, *running_modules_, declared_);
        driver_ = opened.driver;
        settings_ = config.settings_of(opened.driver);
        auto_fell_back_ = opened.fell_back;
        reason_ = std::move(opened.reason);
        actuator_ = std::move(opened.actuator);
    } catch (const drivers::SettingError&) {
        throw;  // names its file:line already
    } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(config.where("daemon", "driver") + error.what());
    } catch (const DeviceError& error) {
        throw DeviceError(config.where(driver_, "") + error.what());
    }
    if (declared_) {
        log::info("actuator: " + actuator::describe(*declared_));
    }
}

void ActuatorHost::attach(Player& player) {
    player_ = &player;
    player_->set_actuator(config_.actuator);
}

ActuatorHost::~ActuatorHost() {
    actuator_.reset();  // closes the module before its record goes
    record_.reset();
}

std::string ActuatorHost::configured_reason() const {
    const std::string where = config_.where("daemon", "driver");  // "file:line: " or ""
    return (where.empty() ? "configured: " : "configured at " + where) +
           "driver = " + config_.driver;
}

std::string ActuatorHost::reason_to_run_sim_instead(
    const std::optional<ModuleInUse>& crashed) const {
    if (driver_ == drivers::kAutoDriver || drivers::is_built_in_driver(driver_)) {
        return {};
    }
    if (crashed && crashed->name == driver_) {
        return "driver module " + driver_ + " (" + crashed->path.string() +
               ") was in use when vibscored last ended without closing it (a crash in it, a "
               "hang, or a kill)";
    }
    if (running_modules_->find(driver_) == nullptr) {
        if (const auto* refused = running_modules_->refused_as(driver_)) {
            return "driver " + driver_ + ": module " + refused->path.string() +
                   " is not loaded: " + refused->reason;
        }
    }
    return {};
}

drivers::AutoChoice ActuatorHost::open_naming(
    const std::string& driver, const std::string& reason, const drivers::ModuleCatalog& modules,
    const std::optional<actuator::Declaration>& declared) {
    const auto open_configured = [this, &modules, &declared](const std::string& name) {
        return open(name, config_.settings_of(name), modules, declared);
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
    const drivers::ModuleCatalog& modules, const std::optional<actuator::Declaration>& declared) {
    std::optional<ModuleRecord> record;
    if (const auto* module = drivers::is_built_in_driver(driver) ? nullptr : modules.find(driver)) {
        record.emplace(config_.module_record, ModuleInUse{driver, module->path});
    }
    try {
        auto actuator = drivers::make_actuator(driver, settings, modules, declared);
        if (record) {
            record_.emplace(std::move(*record));  // removed once this actuator has closed
        }
        return actuator;
    } catch (const drivers::SettingError& error) {
        throw drivers::SettingError(error.key(), config_.where(driver, error.key()) + error.what());
    }
}

std::vector<drivers::DriverInfo> ActuatorHost::drivers() const {
    const std::lock_guard lock(modules_mutex_);
    return drivers::available_drivers(*modules_);
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
    const std::optional<actuator::Declaration> declared = config_.actuator;
    std::shared_ptr<const drivers::ModuleCatalog> modules;
    {
        const std::lock_guard lock(modules_mutex_);
        modules = modules_;
    }
    // The player must never point at a closed backend, not even for a moment.
    drivers::DisconnectedActuator switching("switching to driver " + driver);
    if (player_) {
        player_->stop_all("driver-switch");
        player_->replace_actuator(switching);
    }
    actuator_.reset();
    record_.reset();
    drivers::AutoChoice opened;
    try {
        opened = open_naming(driver, reason, *modules, declared);
    } catch (const std::exception& error) {
        log::error("driver " + driver + " failed to open (" + error.what() + "); reopening " +
                   driver_);
        follows_config_ = false;  // a reload tries the configuration's driver again
        try {
            actuator_ = open(driver_, settings_, *running_modules_, declared_);
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
    running_modules_ = std::move(modules);
    declared_ = declared;
    reason_ = std::move(opened.reason);
    auto_fell_back_ = opened.fell_back;
    follows_config_ = follows_config;
    if (follows_config) {
        configured_ = config_.driver;
    }
    log::info("driver is now " + driver_);
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
    const auto fresh = modules_of(config_);
    {
        const std::lock_guard lock(modules_mutex_);
        modules_ = fresh;
    }
    // A module reopens when its file changed (an upgrade), not because the directory was
    // scanned again.
    const bool module_changed = !drivers::is_built_in_driver(driver_) && driver_ != "none" &&
                                !fresh->same_module(*running_modules_, driver_);
    // Only the sim is made of the declaration; a real backend drives whatever is on the board.
    // A new declaration reopens only a backend that cannot take it in place (the sim when its
    // kind, brake or accelerometer would change): what plays goes on otherwise.
    const bool redeclared_in_place =
        !declaration_changed || (config_.actuator && declared_ && actuator_ &&
                                 actuator_->take_declaration(*config_.actuator));
    const bool differs = config_.driver != configured_ || !follows_config_ ||
                         (config_.driver == drivers::kAutoDriver && auto_fell_back_) ||
                         config_.settings_of(driver_) != settings_ || module_changed ||
                         (!redeclared_in_place && driver_ == "sim");
    if (differs) {
        switch_running(config_.driver, configured_reason(), true);
    } else {
        running_modules_ = fresh;
        declared_ = config_.actuator;
        if (declaration_changed && changed_) {
            changed_();  // the bus announces the new declaration
        }
    }
    return differs;
}

}  // namespace vibscore::daemon
