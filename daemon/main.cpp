// vibscored: the vibscore haptics service on the D-Bus system bus.
#include <systemd/sd-daemon.h>

#include <sdbus-c++/sdbus-c++.h>
#include <CLI/CLI.hpp>

#include <csignal>
#include <iostream>

#include "config.h"
#include "daemon/actuator_host.hpp"
#include "daemon/callers.hpp"
#include "daemon/config.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/event_loop.hpp"
#include "daemon/haptics_service.hpp"
#include "daemon/log.hpp"
#include "daemon/player.hpp"
#include "daemon/registry/registry.hpp"

using namespace vibscore;
using namespace vibscore::daemon;

namespace {

constexpr const char* kDefaultConfig = "/etc/vibscore/vibscored.conf";

// The player reports to the service, which is built after it.
class ListenerRelay : public PlayerListener {
  public:
    PlayerListener* target = nullptr;
    void playback_started(std::uint64_t id, const std::string& label) override {
        if (target)
            target->playback_started(id, label);
    }
    void playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) override {
        if (target)
            target->playback_position(id, bar, symbol);
    }
    void playback_finished(std::uint64_t id, const std::string& reason) override {
        if (target)
            target->playback_finished(id, reason);
    }
};

struct Options {
    std::string config = kDefaultConfig;
    bool config_given = false;
    std::string driver, store, shipped;
    bool verbose = false;
    bool list_drivers = false;
};

DaemonConfig read_config(const Options& options) {
    DaemonConfig defaults;
    defaults.shipped = VIBSCORE_CLEFDIR;
    DaemonConfig config = defaults;
    if (options.config_given || std::filesystem::exists(options.config)) {
        config = load_config(options.config, defaults);
    }
    if (!options.driver.empty())
        config.driver = options.driver;
    if (!options.store.empty())
        config.store = options.store;
    if (!options.shipped.empty())
        config.shipped = options.shipped;
    return config;
}

// Driver switches over D-Bus and on SIGHUP: both go through the host, which keeps the player
// pointing at a live backend whatever fails.
class DaemonDrivers final : public DriverControl {
  public:
    DaemonDrivers(const DaemonConfig& config, ActuatorHost& host, Player& player)
        : config_(&config), host_(host), player_(player) {}

    void attach(HapticsService& service) { service_ = &service; }
    void use_config(const DaemonConfig& config) {
        config_ = &config;
        host_.set_drivers_dir(config.drivers_dir);
    }

    std::vector<drivers::DriverInfo> drivers() const override {
        return drivers::available_drivers(config_->drivers_dir);
    }

    void switch_driver(const std::string& driver) override {
        try {
            host_.switch_to(player_, driver, config_->settings_of(driver));
        } catch (...) {
            announce();
            throw;
        }
        announce();
    }

    HapticsService::Settings service_settings() {
        return {host_.driver(), host_.actuator().capabilities().names(),
                config_->separation_ms / 1000.0};
    }

    void announce() {
        if (service_) {
            service_->update_settings(service_settings());
        }
    }

  private:
    const DaemonConfig* config_;
    ActuatorHost& host_;
    Player& player_;
    HapticsService* service_ = nullptr;
};

int serve(const Options& options) {
    DaemonConfig config = read_config(options);
    EventLoop loop;
    ActuatorHost host(config.driver, config.settings_of(config.driver), config.drivers_dir);
    Registry registry(config.shipped, config.store);
    log::info("registry: " + std::to_string(registry.list(DocumentKind::score).size()) +
              " scores, " + std::to_string(registry.list(DocumentKind::clef).size()) +
              " clefs (shipped " + config.shipped.string() + ", store " + config.store.string() +
              ")");
    CallerDirectory callers(config.requests_per_second, config.request_burst);
    ListenerRelay relay;
    Player player(loop, host.actuator(), relay);
    DaemonDrivers daemon_drivers(config, host, player);

    auto connection = sdbus::createSystemBusConnection();
    HapticsService service(*connection, registry, player, callers, daemon_drivers,
                           daemon_drivers.service_settings());
    daemon_drivers.attach(service);
    relay.target = &service;
    auto vanish_watch = connection->addMatch(
        "type='signal',sender='org.freedesktop.DBus',interface='org.freedesktop.DBus',"
        "member='NameOwnerChanged'",
        [&](sdbus::Message& message) {
            std::string name, old_owner, new_owner;
            message >> name >> old_owner >> new_owner;
            if (new_owner.empty() && !name.empty() && name.front() == ':') {
                player.sender_vanished(name);
                callers.forget(name);
            }
        });
    connection->requestName(kBusName);
    BusLoopBinding binding(loop, *connection);

    const auto shut_down = [&] {
        log::info("stopping");
        sd_notify(0, "STOPPING=1");
        player.stop_all("stopped");
        loop.exit(0);
    };
    auto on_term = loop.on_signal(SIGTERM, shut_down);
    auto on_int = loop.on_signal(SIGINT, shut_down);
    auto on_hup = loop.on_signal(SIGHUP, [&] {
        sd_notify(0, "RELOADING=1");
        try {
            DaemonConfig fresh = read_config(options);
            if (fresh.store != config.store || fresh.shipped != config.shipped) {
                log::warning("store and shipped directories change only on restart");
            }
            // Check the new driver settings before stopping anything.
            std::map<std::string, std::string> fresh_settings = fresh.settings_of(fresh.driver);
            drivers::take_common_settings(fresh.driver, fresh_settings);
            callers.set_rate(fresh.requests_per_second, fresh.request_burst);
            const bool driver_changed = fresh.driver != host.driver() ||
                                        fresh.settings_of(fresh.driver) != host.settings() ||
                                        fresh.drivers_dir != config.drivers_dir;
            config = std::move(fresh);
            daemon_drivers.use_config(config);
            if (driver_changed) {
                daemon_drivers.switch_driver(config.driver);
            }
            daemon_drivers.announce();
            log::info("configuration reloaded");
        } catch (const std::exception& error) {
            log::error(std::string("reload failed, keeping the running configuration: ") +
                       error.what());
        }
        sd_notify(0, "READY=1");
    });

    log::info("vibscored " VIBSCORE_VERSION " ready on " + std::string(kBusName) + ", driver " +
              host.driver());
    sd_notify(0, "READY=1\nSTATUS=serving");
    const int code = loop.run();
    player.stop_all("stopped");
    connection->releaseName(kBusName);
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "vibscored - the vibscore haptics service: plays vibrotactile scores on the actuator\n"
        "for callers on the D-Bus system bus (org.vibscore.Haptics1).\n"
        "DBUS_SYSTEM_BUS_ADDRESS points it at another bus (tests, development).\n"
        "Signals: SIGTERM/SIGINT stop playback and exit; SIGHUP reloads the configuration.",
        "vibscored"};
    Options options;
    app.set_version_flag("--version", std::string("vibscored ") + VIBSCORE_VERSION);
    app.add_option("--config", options.config,
                   std::string("configuration file (default ") + kDefaultConfig + ")");
    app.add_option("--driver", options.driver, "actuator backend, overriding the configuration");
    app.add_option("--store", options.store, "directory of composed documents");
    app.add_option("--shipped", options.shipped, "directory of shipped clefs and scores");
    app.add_flag("--verbose", options.verbose, "log every playback");
    app.add_flag("--list-drivers", options.list_drivers, "list the actuator backends and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        return app.exit(error);
    }
    options.config_given = app.count("--config") > 0;
    log::set_verbose(options.verbose);
    if (options.list_drivers) {
        std::filesystem::path drivers_dir = VIBSCORE_DRIVERDIR;
        try {
            drivers_dir = read_config(options).drivers_dir;
        } catch (const std::exception& error) {
            log::warning(std::string("listing the default drivers directory: ") + error.what());
        }
        for (const auto& driver : drivers::available_drivers(drivers_dir)) {
            std::cout << driver.name << "\t" << driver.description << "\n";
        }
        return 0;
    }
    try {
        return serve(options);
    } catch (const std::exception& error) {
        log::error(error.what());
        return 1;
    }
}
