#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <variant>

#include "daemon/config.hpp"

namespace vibscore::daemon {

inline constexpr const char* kDefaultConfigFile = "/etc/vibscore/vibscored.conf";

// Exit status for wrong usage, as every vibscore program uses it (0 success, 1 failure).
inline constexpr int kExitUsage = 2;

// vibscored's command line.
struct CommandLine {
    std::string config = kDefaultConfigFile;
    bool config_given = false;  // a missing default file is fine; a missing given one is not
    std::string driver, store, shipped;
    bool verbose = false;
    bool list_drivers = false;
    bool safe_off = false;  // switch the configured backend off and exit, without serving
};

// Parses the arguments. For --help and --version it prints them and returns 0 to end with; for
// wrong usage it says what is wrong on stderr and returns kExitUsage.
std::variant<CommandLine, int> parse_command_line(int argc, const char* const* argv);

// The configuration the command line asks for: the file (the default one only if it exists),
// then the command line's overrides, over the built-in defaults, with the driver modules of its
// drivers directory tried out (logging each one refused) and, unless for --safe-off, the record
// of the module in use kept in the store. Throws ConfigError. Logs a warning for each section
// that names no driver.
//
// `may_try_modules`, when given, is asked with the store (the command line's or the file's)
// before any module is tried: false (the daemon's restart guard, StartRecord) tries none and runs
// driver sim, without warnings about the sections of modules it did not try.
DaemonConfig read_config(
    const CommandLine& command_line,
    const std::function<bool(const std::filesystem::path& store)>& may_try_modules = {});

}  // namespace vibscore::daemon
