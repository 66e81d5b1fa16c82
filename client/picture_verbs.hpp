#pragma once

#include <ostream>
#include <string>

namespace vibscore::client {

// vibscore show SCORE --svg FILE | --png FILE: the staff as a picture. Returns an exit code.
int show_picture(const std::string& score, const std::string& svg, const std::string& png,
                 std::ostream& out, std::ostream& err);

}  // namespace vibscore::client
