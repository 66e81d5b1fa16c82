#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "daemon/config.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/auto_driver.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/module_record.hpp"
#include "daemon/player.hpp"

namespace vibscore::daemon {

using DriverSettingsMap = std::map<std::string, std::string>;

// The actuator backends: the one running, the configured settings of each, and switching between
// them at run time (D-Bus SwitchDriver, SIGHUP). A switch stops playback and switches the old
// backend off before the new one opens, since both may want the same device (GPIO lines cannot
// be requested twice).
class ActuatorHost {
  public:
    // Opens config.driver with its settings, from the built-in backends or config.modules
    // ("auto": the backend drivers::choose_driver finds). `config` is the daemon's running
    // configuration: every later switch reads the settings and the modules there, so it must
    // outlive the host (a reload replaces its contents, then calls follow_config()).
    //
    // The daemon comes up whatever a driver module did: when the configured driver is a module
    // that was refused at the scan (it hung, crashed or failed its checks while loading, or is
    // not safe to load), or one that was in use when the daemon last ended without closing it
    // (config.module_record names it: a crash in it), the host runs sim instead and logs why.
    // Throws std::invalid_argument (an unknown driver, naming the file:line that names it; a bad
    // setting) or DeviceError when the configured driver will not open.
    explicit ActuatorHost(const DaemonConfig& config);
    ~ActuatorHost();
    ActuatorHost(const ActuatorHost&) = delete;
    ActuatorHost& operator=(const ActuatorHost&) = delete;

    drivers::Actuator& actuator() { return *actuator_; }
    const std::string& driver() const { return driver_; }
    // Why driver() runs, for people (the DriverReason property): the configuration, what auto
    // found or searched, or a run-time switch.
    const std::string& reason() const { return reason_; }
    drivers::Capabilities capabilities() const { return actuator_->capabilities(); }
    // The built-in backends, then the driver modules found by the last scan. Loads nothing, and
    // may be called from another thread than the one that switches.
    std::vector<drivers::DriverInfo> drivers() const;

    // The player that plays on the actuator: stopped and pointed at the new backend on a switch,
    // and told the declared actuator ([actuator]) now and after every reload.
    void attach(Player& player);
    // The actuator [actuator] declares, as the player uses it.
    const std::optional<actuator::Declaration>& declaration() const { return config_.actuator; }
    // Called after every switch attempt, since even a failed one may leave another backend, and
    // when a reload changes only the declared actuator.
    void on_change(std::function<void()> changed) { changed_ = std::move(changed); }

    // Ends playback with reason "driver-switch" and opens `driver` with its configured settings.
    // When that fails the previous backend is reopened and the error is rethrown; if even that
    // fails, the player is left with a disconnected actuator that fails every playback with the
    // reason. Throws std::invalid_argument for an unknown driver or a bad setting.
    void switch_to(const std::string& driver);

    // After the running configuration changed: takes its driver modules, and switches to its
    // driver when the driver, its settings or the running module's file differ from what runs,
    // or what runs came from a run-time switch (or ran sim in place of a refused module). With
    // driver = auto it chooses again when the last choice fell back to sim (a device may have
    // appeared since); and when the sim runs and the declared actuator it simulates changed.
    // Hands the player the declaration. Returns whether it switched.
    bool follow_config();

  private:
    // What runs and why: `driver` opened (or, for "auto", what it chose) in place of the
    // running backend. Changes nothing when it throws.
    void switch_running(const std::string& driver, const std::string& reason, bool follows_config);
    void open_in_place_of_running(const std::string& driver, const std::string& reason,
                                  bool follows_config);
    drivers::AutoChoice open_naming(const std::string& driver, const std::string& reason,
                                    const drivers::ModuleCatalog& modules,
                                    const std::optional<actuator::Declaration>& declared);
    // The reason of a driver the configuration names.
    std::string configured_reason() const;
    std::unique_ptr<drivers::Actuator> open(const std::string& driver,
                                            const DriverSettingsMap& settings,
                                            const drivers::ModuleCatalog& modules,
                                            const std::optional<actuator::Declaration>& declared);
    // Why the configured driver must not be opened at start ("" when it may be).
    std::string reason_to_run_sim_instead(const std::optional<ModuleInUse>& crashed) const;

    const DaemonConfig& config_;
    Player* player_ = nullptr;
    std::function<void()> changed_;
    // What runs: the backend, the name, settings, modules and declared actuator it was opened
    // with, and the record of the module in use (before the actuator: the record goes once the
    // module has closed).
    std::string driver_;
    DriverSettingsMap settings_;
    std::shared_ptr<const drivers::ModuleCatalog> running_modules_;
    std::optional<actuator::Declaration> declared_;
    std::optional<ModuleRecord> record_;
    std::string configured_;       // the configuration's driver when it was last followed
    bool follows_config_ = true;   // false after a run-time switch
    bool auto_fell_back_ = false;  // auto found nothing and runs sim
    std::string reason_;
    std::unique_ptr<drivers::Actuator> actuator_;
    // The modules of the running configuration, which drivers() lists.
    mutable std::mutex modules_mutex_;
    std::shared_ptr<const drivers::ModuleCatalog> modules_;
};

}  // namespace vibscore::daemon
