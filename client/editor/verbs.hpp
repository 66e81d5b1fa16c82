#pragma once

#include <ostream>
#include <string>

#include "score/score.hpp"

namespace vibscore::editor {

struct ShowRequest {
    std::string score;    // a registry name or a VibScore file
    int width = 0;        // 0: the terminal's width (80 when not a terminal)
    bool colour = false;  // ANSI colours even when stdout is not a terminal
};

// The score `show` draws: a VibScore file, or a registry score fetched from vibscored. Throws
// DocumentError or DaemonError.
Score read_score_to_show(const std::string& score);

// `vibscore show NAME|FILE`: the score as staff notation. Returns an exit code.
int show_score(const ShowRequest& request, std::ostream& out, std::ostream& err);

}  // namespace vibscore::editor
