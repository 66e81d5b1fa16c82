#pragma once

#include "daemon/actuator_host.hpp"
#include "daemon/config.hpp"

namespace vibscore::daemon {

// SIGHUP: `fresh`, the configuration read again, becomes the running one. The new driver (known,
// or a module of fresh.modules) and its common settings are checked before anything changes, so
// a bad file changes nothing (ConfigError or std::invalid_argument naming its file:line). Then the
// limits (admission reads the running ones at each request) and the device clefs ([clefs]) apply
// at once, to the next Play, without touching a
// playback in progress; the backend is reopened if its driver, settings or drivers directory
// changed; when that fails, the host runs the previous backend and the error is rethrown. The store
// and shipped directories change only on restart: they keep their running values, and a warning
// says so.
void reload_config(DaemonConfig& running, DaemonConfig fresh, ActuatorHost& host);

}  // namespace vibscore::daemon
