#pragma once

#include "common/unique_fd.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <utility>

namespace vibscore::drivers {

// A CSV record of every command a simulated actuator received:
//   time_ns,amplitude,frequency_hz,response
// Each line goes out in one write() on an unbuffered descriptor, so another process (a test, a
// benchmark) can follow the file while it grows and never sees half a line.
class TraceFile {
  public:
    // Creates the file with the header, or appends to it when it has lines already (a crashed
    // run's, which --safe-off and the restarted daemon keep; the times are CLOCK_MONOTONIC, so
    // the runs of one boot stay in order). Throws std::runtime_error naming the path and the
    // errno text when it cannot.
    explicit TraceFile(std::filesystem::path path);

    TraceFile(TraceFile&&) noexcept = default;
    TraceFile& operator=(TraceFile&&) noexcept = default;

    // Appends one line. Numbers are written in their shortest form that reads back exactly.
    // Throws std::runtime_error naming the path and the errno text when the write fails.
    void record(std::int64_t time_ns, double amplitude, double frequency_hz, double response);

    const std::filesystem::path& path() const { return path_; }

  private:
    void write_line(const char* data, std::size_t size);

    std::filesystem::path path_;
    UniqueFd fd_;  // closed on every exit path, a failed header write included
};

}  // namespace vibscore::drivers
