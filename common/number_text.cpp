#include "common/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

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

std::string rounded_text(double value, int significant) {
    if (value == 0.0 || !std::isfinite(value)) {
        return number_text(value);
    }
    // Fixed notation with as many decimals as the significant digits leave (never %g's
    // exponents: nobody writes 3.6e+06 seconds or 1.2e-05 seconds), trailing zeros dropped.
    const int exponent = static_cast<int>(std::floor(std::log10(std::abs(value))));
    return fixed_text(value, std::max(0, significant - 1 - exponent));
}

std::string fixed_text(double value, int places) {
    char buffer[400];  // %f of the largest double has 309 digits before the point
    std::snprintf(buffer, sizeof buffer, "%.*f", places, value);
    std::string text = buffer;
    if (text.find('.') != std::string::npos) {
        text.erase(text.find_last_not_of('0') + 1);
        if (text.back() == '.') {
            text.pop_back();
        }
    }
    return text;
}

std::string hz_text(double hz) {
    return fixed_text(hz, 1) + " Hz";
}

std::string ms_text(double seconds) {
    return fixed_text(seconds * 1000.0, 1) + " ms";
}

}  // namespace vibscore
