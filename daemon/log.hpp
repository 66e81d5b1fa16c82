#pragma once

#include <string_view>

// Log lines on stderr with the sd-daemon(3) priority prefix, so journald files them at the
// right level when the daemon runs under systemd and a terminal shows them plainly otherwise.
namespace vibscore::log {

void error(std::string_view message);
void warning(std::string_view message);
void info(std::string_view message);
void debug(std::string_view message);

// Debug lines are dropped unless enabled (vibscored --verbose).
void set_verbose(bool verbose);

}  // namespace vibscore::log
