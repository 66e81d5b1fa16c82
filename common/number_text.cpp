#include "common/number_text.hpp"

#include <charconv>
#include <cmath>

namespace vibscore {

std::string number_text(double value) {
    char buffer[64];
    // Fixed notation reads naturally between 0.0001 and 1e15; beyond, scientific is shorter.
    const double magnitude = std::abs(value);
    const auto format = magnitude == 0.0 || (magnitude >= 1e-4 && magnitude < 1e15)
                            ? std::chars_format::fixed
                            : std::chars_format::general;
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value, format);
    return error == std::errc() ? std::string(buffer, end) : std::string("?");
}

}  // namespace vibscore
