#include "daemon/command_line.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>

#include "common/log.hpp"
#include "config.h"
#include "daemon/calibration_state.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/module_record.hpp"
#include "json/build_tree.hpp"

namespace vibscore::daemon {

std::variant<CommandLine, int> parse_command_line(int argc, const char* const* argv) {
    CLI::App app{
        "vibscored - the vibscore haptics service: plays vibrotactile scores on the actuator\n"
        "for callers on the D-Bus system bus (org.vibscore.Haptics1).\n"
        "DBUS_SYSTEM_BUS_ADDRESS points it at another bus (tests, development).\n"
        "Signals: SIGTERM/SIGINT stop playback and exit; SIGHUP reloads the configuration.",
        "vibscored"};
    CommandLine command_line;
    app.set_version_flag("--version", std::string("vibscored ") + VIBSCORE_VERSION);
    app.add_option("--config", command_line.config,
                   std::string("configuration file (default ") + kDefaultConfigFile + ")");
    app.add_option("--driver", command_line.driver,
                   "actuator backend, overriding the configuration");
    app.add_option("--store", command_line.store, "directory of composed documents");
    app.add_option("--shipped", command_line.shipped,
                   std::string("directory of shipped clefs and scores (default ") +
                       VIBSCORE_CLEFDIR + "; run from a build tree, its checkout's clefs/)");
    app.add_flag("--verbose", command_line.verbose, "log every playback");
    app.add_flag("--list-drivers", command_line.list_drivers,
                 "list the actuator backends and exit");
    app.add_flag("--safe-off", command_line.safe_off,
                 "switch the configured actuator off and exit (the unit's ExecStopPost: it runs "
                 "after a crash too, and leaves the crashed run's sim trace and driver module "
                 "record for the next start)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::CallForVersion& version) {
        return app.exit(version);
    } catch (const CLI::ParseError& error) {
        std::cerr << "vibscored: " << error.what() << "\nRun 'vibscored --help' for usage.\n";
        return kExitUsage;
    }
    command_line.config_given = app.count("--config") > 0;
    return command_line;
}

DaemonConfig read_config(
    const CommandLine& command_line,
    const std::function<bool(const std::filesystem::path& store)>& may_try_modules) {
    DaemonConfig defaults;
    // From a build tree, its checkout's clefs/ (build_tree.hpp); else the installed folder.
    defaults.shipped = shipped_clefs_folder();
    DaemonConfig config = defaults;
    if (command_line.config_given || std::filesystem::exists(command_line.config)) {
        config = load_config(command_line.config, defaults);
    }
    // The modules are tried here, once for this reading of the file (on the bus thread when the
    // daemon reloads), and listed from then on without loading them again.
    const bool try_modules =
        !may_try_modules ||
        may_try_modules(command_line.store.empty() ? config.store
                                                   : std::filesystem::path(command_line.store));
    config.modules = try_modules ? drivers::scan_driver_modules(config.drivers_dir)
                                 : std::make_shared<const drivers::ModuleCatalog>();
    std::vector<std::string> drivers;
    for (const auto& driver : drivers::available_drivers(*config.modules)) {
        drivers.push_back(driver.name);
    }
    for (const auto& warning :
         try_modules ? unknown_sections(config, drivers) : std::vector<std::string>{}) {
        log::warning(warning);
    }
    // A value from the command line has no line in the file for messages to point at.
    auto& daemon_lines = config.setting_lines["daemon"];
    if (!command_line.driver.empty()) {
        config.driver = command_line.driver;
        daemon_lines.erase("driver");
    }
    if (!try_modules) {
        config.driver = "sim";
        daemon_lines.erase("driver");
    }
    if (!command_line.store.empty()) {
        config.store = command_line.store;
        daemon_lines.erase("store");
    }
    if (!command_line.shipped.empty()) {
        config.shipped = command_line.shipped;
        daemon_lines.erase("shipped");
    }
    if (!command_line.safe_off) {
        config.module_record = config.store / kModuleRecordFile;
    }
    use_measured_actuator(config);  // `vibscore calibrate --apply`'s numbers, when kept
    return config;
}

}  // namespace vibscore::daemon
