#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "score/clef.hpp"
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
};

// Lays the notes out as bars of four beats (a bar closes early rather than split a note; rests
// are split at bar lines), rests in the gaps and up to `total_ticks`, a note longer than a whole
// note as tied notes, and a bar with its own clef wherever the tempo changes. `tempi` starts at
// tick 0; each tempo is kept within a clef's limits. Throws DocumentError naming `file` when the
// result would break a score's limits.
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
