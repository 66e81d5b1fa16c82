#include "daemon/playback_ids.hpp"

#include <charconv>
#include <chrono>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>

#include "common/atomic_file.hpp"
#include "common/log.hpp"

namespace vibscore::daemon {

namespace {

constexpr int kRunBits = 32;

// The number in the file; 0 when there is none or it is not one.
std::uint64_t previous_run(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string content = text.str();
    std::uint64_t run = 0;
    const auto [end, error] = std::from_chars(content.data(), content.data() + content.size(), run);
    if (error != std::errc() || (end != content.data() + content.size() && *end != '\n')) {
        return 0;
    }
    return run;
}

}  // namespace

std::uint64_t first_playback_id(const std::filesystem::path& store) {
    const auto file = store / kRunCounterFile;
    std::uint64_t run = (previous_run(file) + 1) & ((std::uint64_t{1} << kRunBits) - 1);
    if (run == 0) {
        run = 1;
    }
    try {
        write_file_atomically(file, std::to_string(run) + "\n");
    } catch (const std::exception& error) {
        const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(
                                 std::chrono::system_clock::now().time_since_epoch())
                                 .count();
        run = static_cast<std::uint64_t>(seconds) & ((std::uint64_t{1} << kRunBits) - 1);
        log::warning(std::string("playback ids: cannot count runs in the store (") + error.what() +
                     "); this run is numbered by the clock instead: " + std::to_string(run));
    }
    return (run << kRunBits) + 1;
}

}  // namespace vibscore::daemon
