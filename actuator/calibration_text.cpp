#include "actuator/calibration_text.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "common/trim.hpp"

namespace vibscore::actuator::calibration::text {

std::vector<CsvLine> csv_lines(const std::string& text) {
    std::vector<CsvLine> lines;
    int number = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
        const auto end = text.find('\n', start);
        const std::string raw =
            text.substr(start, end == std::string::npos ? std::string::npos : end - start);
        ++number;
        const std::string line = trim(raw);
        if (!line.empty()) {
            CsvLine out;
            out.number = number;
            out.text = line;
            out.first = lines.empty();
            std::size_t from = 0;
            while (true) {
                const auto comma = line.find(',', from);
                out.fields.push_back(trim(line.substr(
                    from, comma == std::string::npos ? std::string::npos : comma - from)));
                if (comma == std::string::npos) {
                    break;
                }
                from = comma + 1;
            }
            lines.push_back(std::move(out));
        }
        if (end == std::string::npos) {
            break;
        }
        start = end + 1;
    }
    return lines;
}

bool looks_numeric(const std::string& field) {
    if (field.empty()) {
        return false;
    }
    const char c = field[0];
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

double parse_number(const std::string& field, const std::string& where, const char* column) {
    double value = 0.0;
    const char* begin = field.data();
    const char* end = begin + field.size();
    if (!field.empty() && *begin == '+') {
        ++begin;
    }
    const auto [ptr, ec] = std::from_chars(begin, end, value);
    if (field.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
        throw std::invalid_argument(where + ": " + column + " must be a number, not '" + field +
                                    "'");
    }
    return value;
}

}  // namespace vibscore::actuator::calibration::text
