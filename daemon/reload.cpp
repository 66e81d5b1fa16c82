#include "daemon/reload.hpp"

#include <stdexcept>
#include <string>

#include "common/log.hpp"
#include "common/quoted_text.hpp"
#include "daemon/drivers/auto_driver.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/drivers/driver_settings.hpp"

namespace vibscore::daemon {

void reload_config(DaemonConfig& running, DaemonConfig fresh, ActuatorHost& host) {
    // A driver that does not exist is known now, before playback is stopped for it.
    const drivers::ModuleCatalog none;
    const auto& modules = fresh.modules ? *fresh.modules : none;
    if (fresh.driver != drivers::kAutoDriver && !drivers::is_built_in_driver(fresh.driver) &&
        modules.find(fresh.driver) == nullptr) {
        std::string why;
        if (const auto* refused = modules.refused_as(fresh.driver)) {
            why = ": module " + refused->path.string() + " is not loaded: " + refused->reason;
        } else {
            std::string known;
            for (const auto& driver : drivers::available_drivers(modules)) {
                known += (known.empty() ? "" : ", ") + driver.name;
            }
            why = " (available: " + known + ")";
        }
        throw std::invalid_argument(fresh.where("daemon", "driver") + "unknown driver \"" +
                                    fresh.driver + "\"" + why);
    }
    DriverSettingsMap fresh_settings = fresh.settings_of(fresh.driver);
    try {
        drivers::take_common_settings(fresh.driver, fresh_settings);
    } catch (const drivers::SettingError& error) {
        throw drivers::SettingError(error.key(),
                                    fresh.where(fresh.driver, error.key()) + error.what());
    }
    // The registry was read from these at start; reading another folder now would be a second
    // registry under the same names.
    const auto keep_until_restart = [&](const char* key, const std::filesystem::path& running_dir,
                                        std::filesystem::path& fresh_dir) {
        if (fresh_dir != running_dir) {
            log::warning(fresh.where("daemon", key) + key + " = " +
                         quoted_text(fresh_dir.string()) +
                         " changes only on restart; until then it stays " +
                         shown_text(running_dir.string()));
            fresh_dir = running_dir;
        }
    };
    keep_until_restart("store", running.store, fresh.store);
    keep_until_restart("shipped", running.shipped, fresh.shipped);
    const bool clefs_changed = fresh.device_clefs != running.device_clefs;
    running = std::move(fresh);
    if (clefs_changed) {
        log::info("device clefs: " + describe(running.device_clefs));
    }
    host.follow_config();
    log::info("configuration reloaded");
}

}  // namespace vibscore::daemon
