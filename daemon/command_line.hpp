#pragma once

#include <string>
#include <variant>

#include "daemon/config.hpp"

namespace vibscore::daemon {

inline constexpr const char* kDefaultConfigFile = "/etc/vibscore/vibscored.conf";

// vibscored's command line.
struct CommandLine {
    std::string config = kDefaultConfigFile;
    bool config_given = false;  // a missing default file is fine; a missing given one is not
    std::string driver, store, shipped;
    bool verbose = false;
    bool list_drivers = false;
    bool safe_off = false;  // switch the configured backend off and exit, without serving
};

// Parses the arguments. For --help, --version and wrong usage it prints what CLI11 prints and
// returns the exit status to end with instead.
std::variant<CommandLine, int> parse_command_line(int argc, const char* const* argv);

// The configuration the command line asks for: the file (the default one only if it exists),
// then the command line's overrides, over the built-in defaults. Throws ConfigError.
DaemonConfig read_config(const CommandLine& command_line);

}  // namespace vibscore::daemon
