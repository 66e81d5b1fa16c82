#include "daemon/actuator_host.hpp"

#include <exception>
#include <stdexcept>
#include <utility>

#include "daemon/drivers/disconnected_actuator.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "daemon/log.hpp"

namespace vibscore::daemon {

namespace {

std::shared_ptr<const drivers::ModuleCatalog> modules_of(const DaemonConfig& config) {
    return config.modules ? config.modules : std::make_shared<const drivers::ModuleCatalog>();
}

}  // namespace

ActuatorHost::ActuatorHost(const DaemonConfig& config)
    : config_(config),
      driver_(config.driver),
      settings_(config.settings_of(config.driver)),
      running_modules_(modules_of(config)),
      declared_(config.actuator),
      modules_(running_modules_) {
    const auto crashed = read_module_record(config.module_record);
    remove_module_record(config.module_record);  // about the run that ended; this one starts afresh
    if (crashed && crashed->name != driver_) {
        log::warning("vibscored last ended while driver module " + crashed->name + " (" +
                     crashed->path.string() + ") was in use, without closing it");
    }
    if (const std::string reason = reason_to_run_sim_instead(crashed); !reason.empty()) {
        log::error(reason +
                   "; running driver sim instead, so the daemon serves. `vibscore driver " +
                   driver_ + "` or a reload tries it again");
        driver_ = "sim";
        settings_ = config.settings_of("sim");
    }
    try {
        actuator_ = open(driver_, settings_, *running_modules_, declared_);
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

std::string ActuatorHost::reason_to_run_sim_instead(
    const std::optional<ModuleInUse>& crashed) const {
    if (drivers::is_built_in_driver(driver_)) {
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
    try {
        actuator_ = open(driver, settings, *modules, declared);
    } catch (const std::exception& error) {
        log::error("driver " + driver + " failed to open (" + error.what() + "); reopening " +
                   driver_);
        try {
            actuator_ = open(driver_, settings_, *running_modules_, declared_);
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
    running_modules_ = std::move(modules);
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
    const bool differs = config_.driver != driver_ ||
                         config_.settings_of(config_.driver) != settings_ || module_changed ||
                         (declaration_changed && config_.driver == "sim");
    if (differs) {
        switch_to(config_.driver);
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
