#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vibscore {

// The one reader of INI text (vibscored.conf, a client's --actuator file), so that the daemon
// and the client read one file the same way. Its rules are strict, because a quietly misread
// line runs the device on numbers nobody wrote:
//   - '#' and ';' start a comment at the start of a line or after a blank; anywhere else
//     ("kind = lra#x", "store = /var/lib/vib#score") they are an error, not a cut-short value;
//   - a section header is "[name]" with a non-empty name; anything else starting '[' is an error;
//   - every other line is "key = value" inside a section; a key set twice in a section is an
//     error naming both lines (which one was meant?).
// A section whose header appears twice continues where it left off.
struct IniLine {
    std::string section;  // the section the line opens (a header) or sits in
    std::string key;      // empty for a header
    std::string value;
    std::string where;  // "file:line"
    bool is_header() const { return key.empty(); }
};

// The file is not INI by the rules above; the message is "file:line: what", naming the line's
// text or its key and value (quoted, at most 80 bytes: common/quoted_text.hpp).
class IniError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The headers and settings of `text`, in the order it gives them, spaces around keys and values
// dropped. `file` names it in the lines' `where` and in errors.
std::vector<IniLine> read_ini(const std::string& text, const std::string& file);

// A setting's value as a number, read one way wherever vibscore reads one: the whole text a
// finite decimal number (no blanks, no '+', no hex, no inf or nan); nullopt otherwise. Each key
// then checks its own range and says it in its own words.
std::optional<double> ini_number(std::string_view value);

}  // namespace vibscore
