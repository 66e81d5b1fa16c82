#pragma once

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <thread>

namespace vibscore::testing {

// Polls `condition` until it holds or `timeout` has passed; whether it held. For what a test
// cannot be told about (a file another process writes, an answer that changes after a reload):
// tests wait for a condition, and the timeout is only a bound, never the thing waited for.
// `poll` is how often it looks: finer where the moment it holds is then read off a clock (the
// HIL tier's device timelines).
inline bool wait_until(const std::function<bool()>& condition,
                       std::chrono::milliseconds timeout = std::chrono::seconds(10),
                       std::chrono::microseconds poll = std::chrono::milliseconds(10)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!condition()) {
        if (std::chrono::steady_clock::now() >= deadline) {
            return false;
        }
        std::this_thread::sleep_for(poll);
    }
    return true;
}

// Whether the file at `path` holds `text` within `timeout`: a log line or an output another
// process writes (a missing file is one that does not hold it yet).
inline bool wait_until_file_contains(const std::filesystem::path& path, const std::string& text,
                                     std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    return wait_until(
        [&] {
            std::ifstream in(path, std::ios::binary);
            const std::string content{std::istreambuf_iterator<char>(in), {}};
            return content.find(text) != std::string::npos;
        },
        timeout);
}

}  // namespace vibscore::testing
