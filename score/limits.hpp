#pragma once

#include <cstddef>

// Hard limits on documents. They keep a hostile or broken document from exhausting memory or
// time; each is far above what a real tacton or piece needs. docs/score-format.md lists them.
namespace vibscore::limits {

inline constexpr std::size_t document_bytes = 1 << 20;  // 1 MiB per XML file
inline constexpr std::size_t bars = 10'000;
inline constexpr std::size_t symbols = 100'000;  // notes, rests and blanks in one score
inline constexpr std::size_t clefs_per_score = 32;
inline constexpr std::size_t strings = 6;  // the staff has six lines
inline constexpr std::size_t numbers = 9;  // note heads carry 1..9
inline constexpr std::size_t points_per_string = 4096;
inline constexpr std::size_t title_chars = 256;
inline constexpr std::size_t id_chars = 64;
inline constexpr std::size_t href_chars = 1024;
inline constexpr std::size_t diagnostics = 50;  // reported before giving up on a document

inline constexpr double min_tempo_s = 0.001;
inline constexpr double max_tempo_s = 60.0;
inline constexpr double max_frequency_hz = 20'000.0;
inline constexpr double max_amplitude = 1'000'000.0;
inline constexpr double max_score_seconds = 3600.0;
inline constexpr long long max_serial = 2'147'483'647;

// What one playback may ask of vibscored's playback thread: actuator commands (drives, steps,
// switch-offs) and position cues together, per second of its schedule, with a burst of as many
// at once. Every shipped score stays under a quarter of it; a tempo-0.001 run of rests asked
// 8,000. vibscored ends a playback that asks more with reason "limit-exceeded"
// (docs/daemon.md, Limits).
inline constexpr long long max_playback_cues_per_second = 1000;

}  // namespace vibscore::limits
