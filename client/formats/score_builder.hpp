#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "score/clef.hpp"
#include "score/document_error.hpp"
#include "score/limits.hpp"
#include "score/score.hpp"

namespace vibscore::formats {

// The score's time grid: every length is a whole number of 32nd notes, eight to a quarter.
inline constexpr std::int64_t ticks_per_quarter = 8;

// A note an importer has placed on the grid, with everything the score says about it.
struct GridNote {
    enum class Tie { none, legato, portamento };

    std::int64_t start = 0, length = 1;  // ticks
    int string = 1;
    int number = 1;
    Dynamics dynamics = Dynamics::none;
    Tie tie_to_next = Tie::none;
};

// From tick `at` on, a quarter note lasts `tempo` seconds.
struct TempoChange {
    std::int64_t at = 0;
    double tempo = 1.0;
};

// The clef the user chose for an import, and the name its copies take.
struct ChosenClef {
    std::string name;  // an id: the clef file's stem, e.g. "lra-phone"
    Clef clef;
};

// A clef the imported score declares: the chosen one, or a copy at another tempo.
struct ImportedClef {
    std::string id;
    Clef clef;
    bool retimed = false;  // a copy of the chosen clef with the piece's own tempo
};

struct ImportedScore {
    Score score;  // its Clef declarations carry ids; the caller sets the hrefs
    std::vector<ImportedClef> clefs;
    // What the reader took though the format's documents forbid it, and how it read it (an
    // AHAP trailing comma, a parameter out of range clamped, as Apple's own parser does).
    std::vector<Diagnostic> warnings;
};

// A bar of the imported score holds at most four beats, so a piece longer than this many ticks
// needs more bars than a score may have.
inline constexpr std::int64_t max_import_ticks =
    static_cast<std::int64_t>(limits::bars) * 4 * ticks_per_quarter;

// Refuses a text larger than a score document may be (limits::document_bytes), as reading it
// from a file would: the readers hold to it whoever calls them.
void check_document_size(std::string_view text, const std::string& file);

// Longer than a score may last (limits::max_score_seconds), with the microsecond of slack the
// score reader allows for rounding.
bool past_the_hour(double seconds);

// "3600.062 s", "3600 s", "1.34e+08 s": a length for a message.
std::string seconds_text(double seconds);

// When tick `tick` sounds, in seconds, with each tempo kept within a clef's limits as the score
// will have it. `tempi` is in order and starts at tick 0.
double seconds_at(const std::vector<TempoChange>& tempi, std::int64_t tick);

// Lays the notes out as bars of four beats (a bar closes early rather than split a note; rests
// are split at bar lines), rests in the gaps and up to `total_ticks`, a note longer than a whole
// note as tied notes, and a bar with its own clef wherever the tempo changes. `tempi` starts at
// tick 0; each tempo is kept within a clef's limits. Throws DocumentError naming `file` and the
// limit of a score that the result would break (bars, symbols, seconds, clefs); a piece whose
// length alone breaks one is refused before anything is laid out, so refusing it costs no more
// than reading it.
ImportedScore build_score(std::vector<GridNote> notes, std::vector<TempoChange> tempi,
                          std::int64_t total_ticks, const ChosenClef& chosen, std::string title,
                          const std::string& file);

// The clef id a tempo gets: the chosen clef's name, or NAME-150bpm for another tempo.
std::string clef_id_for(const ChosenClef& chosen, double tempo);

// The number whose amplitude is nearest to `strength` times the clef's strongest number.
int nearest_number(const Clef& clef, double strength);

// The lengths, longest first, that add up to `ticks`; e.g. 10 ticks: quarter and 16th.
std::vector<Length> lengths_for(std::int64_t ticks);

}  // namespace vibscore::formats
