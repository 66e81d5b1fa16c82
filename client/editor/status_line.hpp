#pragma once

#include <optional>
#include <string>

#include "client/editor/position.hpp"
#include "score/score.hpp"

namespace vibscore::editor {

// Columns a line takes on the terminal (UTF-8: one per character).
int columns_of(const std::string& text);
// `text` cut to `width` columns.
std::string fit(std::string text, int width);

// The bottom line of a small screen (40x12), where it is the only line of text. What the
// buttons do is never cut: the symbol being entered goes first where it fits, and the bar
// ("bar 2/3") goes last, right-aligned, where room is left. A message replaces both.
struct StatusParts {
    bool modified = false;
    std::string message;   // what the last action did, or ""
    std::string entering;  // the symbol being entered ("5 quarter s3"), or ""
    std::string hint;      // what the buttons do now
    std::size_t bar = 0;   // 1-based
    std::size_t bars = 0;
};
std::string status_line(const StatusParts& parts, int width);

class EditorModel;

// The keyboard's number keys in one line for a full keyboard's screen (80 columns): the keys a
// newcomer cannot guess from the buttons' hints.
std::string keyboard_hint();

// A symbol as a person names it: "dotted 8th, 5, string 3", "8th rest" (never the document's
// tokens, "8th_dot", "s3").
std::string symbol_words(const Symbol& symbol);

// The note or rest under the cursor while entering ("5 quarter s3", "rest 8th"), or "".
std::string symbol_entered(const EditorModel& model);

}  // namespace vibscore::editor
