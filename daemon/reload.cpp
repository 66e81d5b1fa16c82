#include "daemon/reload.hpp"

#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "daemon/log.hpp"

namespace vibscore::daemon {

void reload_config(DaemonConfig& running, DaemonConfig fresh, ActuatorHost& host,
                   CallerDirectory& callers) {
    DriverSettingsMap fresh_settings = fresh.settings_of(fresh.driver);
    try {
        drivers::take_common_settings(fresh.driver, fresh_settings);
    } catch (const drivers::SettingError& error) {
        throw drivers::SettingError(error.key(),
                                    fresh.where(fresh.driver, error.key()) + error.what());
    }
    if (fresh.store != running.store || fresh.shipped != running.shipped) {
        log::warning("store and shipped directories change only on restart");
        fresh.store = running.store;
        fresh.shipped = running.shipped;
    }
    callers.set_rate(fresh.requests_per_second, fresh.request_burst);
    const bool clefs_changed = fresh.device_clefs != running.device_clefs;
    running = std::move(fresh);
    if (clefs_changed) {
        log::info("device clefs: " + describe(running.device_clefs));
    }
    host.follow_config();
    log::info("configuration reloaded");
}

}  // namespace vibscore::daemon
