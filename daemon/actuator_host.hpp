#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "daemon/drivers/actuator.hpp"
#include "daemon/player.hpp"

namespace vibscore::daemon {

using DriverSettingsMap = std::map<std::string, std::string>;

// Owns the running actuator backend and switches it at run time (D-Bus SwitchDriver, SIGHUP).
// A switch stops playback and switches the old backend off before the new one opens, since
// both may want the same device (GPIO lines cannot be requested twice).
class ActuatorHost {
  public:
    ActuatorHost(std::string driver, DriverSettingsMap settings, std::filesystem::path drivers_dir);

    drivers::Actuator& actuator() { return *actuator_; }
    const std::string& driver() const { return driver_; }
    const DriverSettingsMap& settings() const { return settings_; }

    // Ends playback with reason "driver-switch" and opens `driver`. When that fails the
    // previous backend is reopened and the error is rethrown; if even that fails, the player
    // is left with a disconnected actuator that fails every playback with the reason.
    void switch_to(Player& player, const std::string& driver, const DriverSettingsMap& settings);

    void set_drivers_dir(std::filesystem::path drivers_dir) {
        drivers_dir_ = std::move(drivers_dir);
    }

  private:
    std::unique_ptr<drivers::Actuator> open(const std::string& driver,
                                            const DriverSettingsMap& settings) const;

    std::string driver_;
    DriverSettingsMap settings_;
    std::filesystem::path drivers_dir_;
    std::unique_ptr<drivers::Actuator> actuator_;
};

}  // namespace vibscore::daemon
