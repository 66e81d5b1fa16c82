// vibscored: the vibscore haptics service on the D-Bus system bus. This file only wires the
// parts together: the loop, the bus, the objects, the signals; each part holds its own logic.
#include <systemd/sd-daemon.h>

#include <sdbus-c++/sdbus-c++.h>

#include <csignal>
#include <iostream>
#include <optional>

#include "common/event_loop.hpp"
#include "common/log.hpp"
#include "config.h"
#include "daemon/actuator_host.hpp"
#include "daemon/authority.hpp"
#include "daemon/bus_credentials.hpp"
#include "daemon/calibrator.hpp"
#include "daemon/callers.hpp"
#include "daemon/command_line.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/haptics_service.hpp"
#include "daemon/module_record.hpp"
#include "daemon/playback_ids.hpp"
#include "daemon/playback_thread.hpp"
#include "daemon/polkit_authority.hpp"
#include "daemon/registry/registry.hpp"
#include "daemon/reload.hpp"
#include "daemon/virtual_vibra/virtual_vibra.hpp"
#include "daemon/watchdog.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"

using namespace vibscore;
using namespace vibscore::daemon;

namespace {

// A bad configuration fails here as it fails a start: exit 1, so that a script or a package's
// check does not take the list for the configured one. The default directory's drivers are
// still listed after the error, to help whoever fixes the file choose a driver.
int list_drivers(const CommandLine& command_line) {
    std::vector<drivers::DriverInfo> drivers;
    int status = 0;
    try {
        // read_config() has already tried each module of the configured directory in a child.
        const DaemonConfig config = read_config(command_line);
        drivers = drivers::available_drivers(*config.modules);
    } catch (const std::exception& error) {
        log::error(error.what());
        log::warning("listing the drivers of the default directory " VIBSCORE_DRIVERDIR " instead");
        drivers = drivers::available_drivers(std::filesystem::path(VIBSCORE_DRIVERDIR));
        status = 1;
    }
    for (const auto& driver : drivers) {
        std::cout << driver.name << "\t" << driver.description << "\n";
    }
    return status;
}

// A [clefs] line naming a clef nobody installed would only show when a playback falls back.
void warn_about_missing_device_clefs(const DaemonConfig& config, const Registry& registry) {
    for (const auto& warning : missing_device_clefs(config, registry)) {
        log::warning(warning);
    }
}

// After the daemon ended, however it ended (SIGKILL, a crash): the configured backend, opened
// and switched off (GPIO lines driven low), then closed again.
int safe_off(const CommandLine& command_line) {
    const DaemonConfig config = read_config(command_line);
    ActuatorHost host(config);
    host.actuator().off();
    log::info("safe-off: " + host.driver() + " switched off");
    return 0;
}

// The bus thread's loop takes these signals through a signalfd. Blocked before any other thread
// starts (the playback thread, a GPIO backend's PWM thread), so that every thread inherits the
// mask and the kernel never hands one to a thread that would die of it.
void block_handled_signals() {
    sigset_t mask;
    sigemptyset(&mask);
    for (const int signo : {SIGTERM, SIGINT, SIGHUP}) {
        sigaddset(&mask, signo);
    }
    pthread_sigmask(SIG_BLOCK, &mask, nullptr);
}

int serve(const CommandLine& command_line) {
    block_handled_signals();
    // Noted in the store until the daemon is ready: a start after too many that never were runs
    // sim without trying any module (module_record.hpp).
    std::optional<StartRecord> start;
    DaemonConfig config = read_config(command_line, [&start](const std::filesystem::path& store) {
        start.emplace(store / kStartRecordFile);
        const std::string why = start->safe_start_reason();
        if (!why.empty()) {
            log::error(why);
        }
        return why.empty();
    });
    EventLoop loop;
    ActuatorHost host(config);
    Registry registry(config.shipped, config.store);
    log::info("registry: " + std::to_string(registry.list(DocumentKind::score).size()) +
              " scores, " + std::to_string(registry.list(DocumentKind::clef).size()) +
              " clefs (shipped " + config.shipped.string() + ", store " + config.store.string() +
              ")");
    if (!config.device_clefs.empty()) {
        log::info("device clefs: " + describe(config.device_clefs));
    }
    log_clef_fits(registry, config.device_clefs);
    warn_about_missing_device_clefs(config, registry);
    // From here on every actuator call happens on the playback thread.
    PlaybackThread playback(loop, host.actuator(),
                            {first_playback_id(config.store), config.rt_priority});
    playback.call([&host](Player& player) { host.attach(player); });

    auto connection = sdbus::createSystemBusConnection();
    BusCredentials credentials(*connection);
    CallerDirectory callers([&](const std::string& sender) { return credentials.uid_of(sender); });
    BusPolkitAuthority polkit(*connection);
    Authorizer authorizer(polkit);
    // Before the service, which tells it of every playback's end: gone only after the service.
    Calibrator calibrator(config, playback, host);
    HapticsService service(*connection, config, registry, playback, callers, host, authorizer);
    service.set_calibrator(&calibrator);
    // The kernel's vibra for programs that only know force feedback (feedbackd, games, fftest).
    const auto vibra_settings = parse_virtual_vibra_settings(config.settings_of("virtual-vibra"));
    std::optional<VirtualVibra> vibra;
    if (vibra_settings.enabled) {
        vibra.emplace(
            loop,
            [&playback](const auto& work) {
                playback.call([work](Player& player) { work(player); });
            },
            vibra_settings, config.separation_ms / 1000.0,
            // The configuration of now: a reload's [limits] apply from the next effect.
            [&config, usage = vibra_settings.usage] { return config.limits.max_on_time(usage); });
    }
    dbus::request_name(*connection, haptics1::kBusName);
    BusLoopBinding binding(loop, *connection);
    // Pinged while both threads answer (WatchdogSec= in the unit).
    const Watchdog watchdog(loop, playback);

    const auto stop_playback = [&] {
        try {
            playback.call([](Player& player) { player.stop_all(kServiceStopped); });
        } catch (const PlaybackStuck& stuck) {
            log::error(std::string("stopping: ") + stuck.what());
        }
    };
    const auto shut_down = [&] {
        log::info("stopping");
        sd_notify(0, "STOPPING=1");
        stop_playback();
        loop.exit(0);
    };
    auto on_term = loop.on_signal(SIGTERM, shut_down);
    auto on_int = loop.on_signal(SIGINT, shut_down);
    auto on_hup = loop.on_signal(SIGHUP, [&] {
        sd_notify(0, "RELOADING=1");
        try {
            // The running configuration and the host live as long as the daemon;
            // the fresh configuration goes with the work.
            playback.call([&config, &host, fresh = read_config(command_line)](Player&) mutable {
                reload_config(config, std::move(fresh), host);
            });
            log_clef_fits(registry, config.device_clefs);  // refitted to what was declared now
            warn_about_missing_device_clefs(config, registry);
        } catch (const std::exception& error) {
            log::error(std::string("reload failed, keeping the running configuration: ") +
                       error.what());
        }
        sd_notify(0, "READY=1");
    });

    log::info("vibscored " VIBSCORE_VERSION " ready on " + std::string(haptics1::kBusName) +
              ", driver " + host.driver());
    sd_notify(0, "READY=1\nSTATUS=serving");
    if (start) {
        start->ready();
    }
    const int code = loop.run();
    stop_playback();
    dbus::release_name(*connection, haptics1::kBusName);
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    const auto parsed = parse_command_line(argc, argv);
    if (const int* exit_status = std::get_if<int>(&parsed)) {
        return *exit_status;
    }
    const auto& command_line = std::get<CommandLine>(parsed);
    log::set_verbose(command_line.verbose);
    if (command_line.list_drivers) {
        return list_drivers(command_line);
    }
    try {
        if (command_line.safe_off) {
            return safe_off(command_line);
        }
        return serve(command_line);
    } catch (const std::exception& error) {
        log::error(error.what());
        return 1;
    }
}
