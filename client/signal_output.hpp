#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "daemon/render/performance.hpp"

namespace vibscore::client {

enum class SignalFormat { csv, wav };

// The largest signal file render writes: 4 GiB, where a WAV file's 32-bit sizes end. A CSV is
// held to the same, so `--out x.csv` cannot fill a disk with what `--out x.wav` refuses.
inline constexpr std::uint64_t kMaxSignalFileBytes = std::uint64_t{1} << 32;

// A signal file that would be larger than allowed; nothing has been written.
class SignalTooLarge : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The bytes of the CSV of `samples` samples, as far as they are known without the signal: its
// rows are "t,y\n" with each number at least 1 and at most kMaxNumberChars characters.
inline constexpr std::uint64_t kMaxNumberChars = 24;  // "-2.2250738585072014e-308"
struct CsvSize {
    std::uint64_t least = 0, most = 0;
};
CsvSize csv_size_bounds(std::uint64_t samples);

// The exact bytes of the CSV write_signal writes at `rate`: the signal is rendered and its rows
// counted, and nothing is written.
std::uint64_t csv_size(const render::Performance& performance, std::uint32_t rate);

// Tells the format from the file name's extension (.csv or .wav); throws std::invalid_argument.
SignalFormat signal_format_for(const std::filesystem::path& path);

// Writes the performance's drive signal at `rate` samples per second, in clef units:
// csv: a header line "t,y", then one row per sample with t = k / rate seconds;
// wav: mono 32-bit IEEE float samples.
// The file appears complete or not at all: it is written beside the target and renamed over it.
// A file that would be larger than `max_bytes` is refused with SignalTooLarge, naming the limit
// and the size, before anything is written (a CSV between its bounds is counted first).
// Returns the number of samples written. Throws std::runtime_error naming the path on failure.
std::uint64_t write_signal(const render::Performance& performance, std::uint32_t rate,
                           const std::filesystem::path& path,
                           std::uint64_t max_bytes = kMaxSignalFileBytes);

}  // namespace vibscore::client
