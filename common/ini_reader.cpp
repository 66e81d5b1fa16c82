#include "common/ini_reader.hpp"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include "common/quoted_text.hpp"
#include "common/trim.hpp"

namespace vibscore {

namespace {

// Where a comment begins: '#' or ';' at the start of a line or after a blank, as the shipped
// file and the docs write them ("carrier-hz = 20000  # erm only"). npos: no comment.
std::size_t comment_start(const std::string& line) {
    for (std::size_t i = 0; i < line.size(); ++i) {
        if ((line[i] == '#' || line[i] == ';') &&
            (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t' || line[i - 1] == '\r')) {
            return i;
        }
    }
    return std::string::npos;
}

// What is left after the comment holds '#' or ';': "store = /var/lib/vib#score" cut at the '#'
// would quietly use another path.
void refuse_inner_comment_mark(const std::string& content, const std::string& where) {
    const auto mark = content.find_first_of("#;");
    if (mark == std::string::npos) {
        return;
    }
    const auto equals = content.find('=');
    const std::string what = equals == std::string::npos || content.front() == '['
                                 ? quoted_text(content)
                                 : shown_text(trim(content.substr(0, equals))) + " = " +
                                       quoted_text(trim(content.substr(equals + 1)));
    throw IniError(where + ": " + what + " holds '" + content[mark] +
                   "', which starts a comment only at the start of a line or after a space; a "
                   "value cannot contain it");
}

}  // namespace

std::vector<IniLine> read_ini(const std::string& text, const std::string& file) {
    std::istringstream lines(text);
    std::string line;
    std::string section;
    int number = 0;
    std::vector<IniLine> read;
    // Where in `read` each section's keys were set, for the message about a repeated key.
    std::map<std::string, std::map<std::string, std::size_t>> set_at;
    while (std::getline(lines, line)) {
        ++number;
        const std::string where = file + ":" + std::to_string(number);
        const auto content = trim(line.substr(0, comment_start(line)));
        if (content.empty()) {
            continue;
        }
        refuse_inner_comment_mark(content, where);
        if (content.front() == '[') {
            if (content.back() != ']' || content.size() < 3) {
                throw IniError(where + ": malformed section header " + quoted_text(content));
            }
            section = trim(content.substr(1, content.size() - 2));
            read.push_back({section, {}, {}, where});
            continue;
        }
        const auto equals = content.find('=');
        if (equals == std::string::npos) {
            throw IniError(where + ": expected \"key = value\", found " + quoted_text(content));
        }
        const auto key = trim(content.substr(0, equals));
        const auto value = trim(content.substr(equals + 1));
        if (section.empty()) {
            throw IniError(where + ": " + quoted_text(key) + " is outside any [section]");
        }
        if (key.empty()) {  // "= 3": a value of no key
            throw IniError(where + ": expected \"key = value\", found " + quoted_text(content));
        }
        auto& first_of_section = set_at[section];
        if (const auto first = first_of_section.find(key); first != first_of_section.end()) {
            const IniLine& earlier = read[first->second];
            throw IniError(where + ": " + shown_text(key) + " = " + quoted_text(value) + " sets [" +
                           shown_text(section) + "] " + shown_text(key) + " again (" +
                           earlier.where + " set it to " + quoted_text(earlier.value) +
                           "); keep one of them");
        }
        first_of_section.emplace(key, read.size());
        read.push_back({section, key, value, where});
    }
    return read;
}

std::optional<double> ini_number(std::string_view value) {
    double number = 0.0;
    const char* const end = value.data() + value.size();
    const auto [ptr, error] = std::from_chars(value.data(), end, number);
    if (value.empty() || error != std::errc{} || ptr != end || !std::isfinite(number)) {
        return std::nullopt;
    }
    return number;
}

}  // namespace vibscore
