#pragma once

#include <string>
#include <string_view>

namespace vibscore {

// Text a client chose (a name, an href, an app id) or a configuration file holds (a value, a
// key), in double quotes, fit for a message or a log line: at most 80 bytes of it (cut before a
// UTF-8 character, not inside one; then "... (N bytes)"), and control characters as \xNN, so
// that a megabyte of it cannot flood a log and a NUL or newline in it cannot cut a message short
// or forge a journal line.
std::string quoted_text(std::string_view text);

// The same without the quotes, for text a message shows bare (a configuration key, a section
// name): "[sim] model", not "[\"sim\"] \"model\"".
std::string shown_text(std::string_view text);

}  // namespace vibscore
