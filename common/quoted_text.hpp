#pragma once

#include <string>
#include <string_view>

namespace vibscore {

// Text a client chose (a name, an href, an app id), in double quotes, fit for a message or a
// log line: at most 80 bytes of it (then its size), and control characters as \xNN, so that a
// megabyte of it cannot flood a log and a NUL or newline in it cannot cut a message short or
// forge a journal line.
std::string quoted_text(std::string_view text);

}  // namespace vibscore
