#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "daemon/config.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/auto_driver.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/player.hpp"

namespace vibscore::daemon {

using DriverSettingsMap = std::map<std::string, std::string>;

// The actuator backends: the one running, the configured settings of each, and switching between
// them at run time (D-Bus SwitchDriver, SIGHUP). A switch stops playback and switches the old
// backend off before the new one opens, since both may want the same device (GPIO lines cannot
// be requested twice).
class ActuatorHost {
  public:
    // Opens config.driver with its settings ("auto": the backend drivers::choose_driver finds).
    // `config` is the daemon's running configuration: every later switch reads the settings and
    // the drivers directory there, so it must outlive the host (a reload replaces its contents,
    // then calls follow_config()).
    explicit ActuatorHost(const DaemonConfig& config);

    drivers::Actuator& actuator() { return *actuator_; }
    const std::string& driver() const { return driver_; }
    // Why driver() runs, for people (the DriverReason property): the configuration, what auto
    // found or searched, or a run-time switch.
    const std::string& reason() const { return reason_; }
    drivers::Capabilities capabilities() const { return actuator_->capabilities(); }
    // The built-in backends, then the driver modules of the configured drivers directory.
    std::vector<drivers::DriverInfo> drivers() const;

    // The player that plays on the actuator: stopped and pointed at the new backend on a switch.
    void attach(Player& player) { player_ = &player; }
    // Called after every switch attempt, since even a failed one may leave another backend.
    void on_change(std::function<void()> changed) { changed_ = std::move(changed); }

    // Ends playback with reason "driver-switch" and opens `driver` with its configured settings.
    // When that fails the previous backend is reopened and the error is rethrown; if even that
    // fails, the player is left with a disconnected actuator that fails every playback with the
    // reason. Throws std::invalid_argument for an unknown driver or a bad setting.
    void switch_to(const std::string& driver);

    // After the running configuration changed: switches to its driver when the driver, its
    // settings or the drivers directory differ from what runs, or what runs came from a
    // run-time switch. With driver = auto it chooses again when the last choice fell back to
    // sim (a device may have appeared since). Returns whether it switched.
    bool follow_config();

  private:
    // What runs and why: `driver` opened (or, for "auto", what it chose) in place of the
    // running backend. Changes nothing when it throws.
    void switch_running(const std::string& driver, const std::string& reason, bool follows_config);
    void open_in_place_of_running(const std::string& driver, const std::string& reason,
                                  bool follows_config);
    drivers::AutoChoice open_naming(const std::string& driver, const std::string& reason) const;
    // The reason of a driver the configuration names.
    std::string configured_reason() const;
    std::unique_ptr<drivers::Actuator> open(const std::string& driver,
                                            const DriverSettingsMap& settings,
                                            const std::filesystem::path& drivers_dir) const;

    const DaemonConfig& config_;
    Player* player_ = nullptr;
    std::function<void()> changed_;
    // What runs: the backend, the name, settings and drivers directory it was opened with.
    std::string driver_;
    DriverSettingsMap settings_;
    std::filesystem::path drivers_dir_;
    std::string configured_;       // the configuration's driver when it was last followed
    bool follows_config_ = true;   // false after a run-time switch
    bool auto_fell_back_ = false;  // auto found nothing and runs sim
    std::string reason_;
    std::unique_ptr<drivers::Actuator> actuator_;
};

}  // namespace vibscore::daemon
