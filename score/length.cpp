#include "score/length.hpp"

#include <array>

namespace vibscore {

namespace {

struct LengthInfo {
    std::string_view name;
    double beats;
};

constexpr std::array<LengthInfo, length_count> kLengths{{
    {"whole", 4.0},
    {"half_dot", 3.0},
    {"half", 2.0},
    {"quarter_dot", 1.5},
    {"quarter", 1.0},
    {"8th_dot", 0.75},
    {"8th", 0.5},
    {"16th_dot", 0.375},
    {"16th", 0.25},
    {"32th", 0.125},
}};

}  // namespace

double beats(Length length) {
    return kLengths.at(static_cast<size_t>(length)).beats;
}

std::string_view to_string(Length length) {
    return kLengths.at(static_cast<size_t>(length)).name;
}

std::optional<Length> parse_length(std::string_view text) {
    for (size_t i = 0; i < kLengths.size(); ++i) {
        if (kLengths[i].name == text) {
            return static_cast<Length>(i);
        }
    }
    return std::nullopt;
}

std::string_view length_spellings() {
    return "whole, half_dot, half, quarter_dot, quarter, 8th_dot, 8th, 16th_dot, 16th, 32th";
}

}  // namespace vibscore
