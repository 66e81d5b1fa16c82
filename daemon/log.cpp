#include "daemon/log.hpp"

#include <unistd.h>

#include <string>

namespace vibscore::log {

namespace {

bool g_verbose = false;

void write_line(const char* prefix, std::string_view message) {
    std::string line(prefix);
    line.append(message);
    line += '\n';
    // One write per line keeps lines whole when several processes share the terminal.
    [[maybe_unused]] const auto written = ::write(STDERR_FILENO, line.data(), line.size());
}

}  // namespace

void error(std::string_view message) {
    write_line("<3>", message);
}
void warning(std::string_view message) {
    write_line("<4>", message);
}
void info(std::string_view message) {
    write_line("<6>", message);
}
void debug(std::string_view message) {
    if (g_verbose) {
        write_line("<7>", message);
    }
}
void set_verbose(bool verbose) {
    g_verbose = verbose;
}

}  // namespace vibscore::log
