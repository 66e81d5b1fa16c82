#pragma once

#include <string>
#include <string_view>

namespace vibscore {

// The blanks a person's text file holds around a key, a value or a field: spaces, tabs, and the
// carriage return a file written on Windows ends each line with.
inline constexpr std::string_view kBlanks = " \t\r";

// `text` without kBlanks at either end ("" when it is all blanks). Newlines are not blanks:
// the line readers split at them first, and a newline inside a value is the caller's to refuse.
inline std::string trim(std::string_view text) {
    const auto begin = text.find_first_not_of(kBlanks);
    if (begin == std::string_view::npos) {
        return {};
    }
    return std::string(text.substr(begin, text.find_last_not_of(kBlanks) - begin + 1));
}

}  // namespace vibscore
