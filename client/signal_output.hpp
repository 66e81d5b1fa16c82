#pragma once

#include <cstdint>
#include <filesystem>

#include "daemon/render/performance.hpp"

namespace vibscore::client {

enum class SignalFormat { csv, wav };

// Tells the format from the file name's extension (.csv or .wav); throws std::invalid_argument.
SignalFormat signal_format_for(const std::filesystem::path& path);

// Writes the performance's drive signal at `rate` samples per second, in clef units:
// csv: a header line "t,y", then one row per sample with t = k / rate seconds;
// wav: mono 32-bit IEEE float samples.
// The file appears complete or not at all: it is written beside the target and renamed over it.
// Returns the number of samples written. Throws std::runtime_error naming the path on failure.
std::uint64_t write_signal(const render::Performance& performance, std::uint32_t rate,
                           const std::filesystem::path& path);

}  // namespace vibscore::client
