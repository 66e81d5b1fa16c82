#pragma once

#include <ostream>

#include "client/editor/staff_layout.hpp"
#include "score/score.hpp"

namespace vibscore::client {

struct StaffTextOptions {
    int width = 80;       // columns; the staff breaks into systems at bar lines to fit
    bool colour = false;  // ANSI colours (the clef boxes cyan / white / magenta by beat count)
};

// `vibscore show`: the title, then the score drawn as staff systems (thesis Fig. 4.1), painted
// from the editor's staff layout.
void print_staff(std::ostream& out, const Score& score, const StaffTextOptions& options);

// One cell range of a layout row as text, with ANSI colour codes when `colour`.
std::string staff_row_text(const editor::StaffLayout& layout, int row, int begin, int end,
                           bool colour);

}  // namespace vibscore::client
