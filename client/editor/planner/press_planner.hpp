#pragma once

#include <cstddef>
#include <vector>

#include "client/editor/editor.hpp"
#include "client/editor/name_entry.hpp"
#include "score/score.hpp"

namespace vibscore::editor {

struct PressPlan {
    std::vector<Button> presses;
    bool reached = false;         // the editor's score equals the target after the presses
    std::size_t states_seen = 0;  // editor states the search looked at
};

// Only tests and benchmarks link the planner (client/editor/meson.build: editor_planner_dep).
// Finds six-button presses that turn the start editor's score into `target` (title aside), by
// driving copies of the real editor: a breadth-first search over the editor's own transitions
// to the nearest state that has entered more of the target, repeated from there. Each step is
// the fewest presses for what it adds; the whole is greedy. Gives up (reached = false) when a
// step would look at more than `state_limit` states.
PressPlan plan_presses(const Editor& start, const Score& target,
                       std::size_t state_limit = 2'000'000);

// Like plan_presses, for a score that holds every symbol already but some of them wrong (a
// rhythm tapped, then strengths to set): progress is how many leading bars and symbols agree
// with `target`, whatever follows them.
PressPlan plan_changes(const Editor& start, const Score& target,
                       std::size_t state_limit = 2'000'000);

// The fewest presses that save a name entry (opened on its proposals) under `name`: a
// breadth-first search of its presses that never types a character off the way to `name` or
// to a proposal (typing one and deleting it again is never the shorter way).
PressPlan plan_name(const NameEntry& start, const std::string& name);

// How much of `target` the score has entered: the number of leading bars-and-symbols that
// agree (ties compared as which neighbours they join), or -1 when the score holds something
// the target does not have at that point.
int entered_prefix(const Score& score, const Score& target);

// The planner's progress: the bars and symbols entered as the target has them, or -1 when the
// score holds something off the target's path. A symbol still being chosen does not count, nor
// a bar holding only that symbol where the target has another bar (entering ran on into it).
int progress(const Editor& editor, const Score& target);

}  // namespace vibscore::editor
