#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "client/editor/position.hpp"
#include "score/score.hpp"

namespace vibscore::editor {

// What the score itself says comes next at `at`: tactons and ringtones repeat (a bar played
// again, a note and a pause taken in turns, a motif on other strings), so the symbol that
// followed the last one before `at` where it came earlier is likely to follow again.
//
// Earlier occurrences are looked for in this order, the latest first within each:
//   1. the same note (string, number, length) or rest, at the same beat of its bar;
//   2. a note or rest of the same length at the same beat of its bar;
//   3. the same note or rest anywhere;
//   4. a note or rest of the same length anywhere.
// A bar played again, on other strings too, is followed beat by beat; within a bar, a note
// followed before is followed again. The symbol after the occurrence is what is returned.
// After a match by length only (2, 4), and after a rest, a note is only a rhythm: `pitch_known`
// is false, and the caller chooses its string, number and marks. After the same note (1, 3)
// the note is returned as it followed. Tied as it was to the one before it, it carries the
// serial of the note before `at`, or a new one that the caller gives that note too
// (tie_to_previous).
struct Recurrence {
    Symbol next;
    bool pitch_known = false;
    bool same_beat = false;  // the occurrence was at the beat of `at` (orders 1 and 2)
};
std::optional<Recurrence> recurrence_at(const Score& score, Position at);

// A note or rest, with the beat of its bar it starts on.
struct Placed {
    const Symbol* symbol;
    double beat;
};
// The notes and rests before `at` in playing order (Blanks take no time and are left out).
std::vector<Placed> placed_before(const Score& score, Position at);
// The beat of its bar that position `at` starts on.
double beat_at(const Score& score, Position at);

// The same note (string, number, length; marks aside) or a rest of the same length.
bool alike(const Symbol& a, const Symbol& b);

// `follower` as it would follow `last`, when it followed `earlier`: tied to `last` as it was
// tied to `earlier` (with `last`'s serial, or one no note of `score` uses yet when `last` is not
// tied), and not tied otherwise.
Note tied_as_before(const Score& score, Note follower, const Note& earlier, const Note& last);

}  // namespace vibscore::editor
