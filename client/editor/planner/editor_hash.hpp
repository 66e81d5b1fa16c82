#pragma once

#include <cstddef>
#include <string>

#include "client/editor/editor.hpp"

// A hash of an editor for the press planner's set of states seen. States are told apart by
// Editor's ==, which compares every part of the state by value; the hash only spreads them, so
// leaving a part out of it costs speed, never a wrong count. Only tests and benchmarks link it.
namespace vibscore::editor {

struct EditorHash {
    std::size_t operator()(const Editor& editor) const;
};

// The score as text: every field the editor can change, in order.
std::string score_text(const Score& score);

}  // namespace vibscore::editor
