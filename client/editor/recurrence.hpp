#pragma once

#include <optional>

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
};
std::optional<Recurrence> recurrence_at(const Score& score, Position at);

}  // namespace vibscore::editor
