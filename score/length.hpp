#pragma once

#include <optional>
#include <string_view>

namespace vibscore {

// The ten note and rest lengths of the thesis (Table 3.1), longest first.
enum class Length {
    whole,
    half_dot,
    half,
    quarter_dot,
    quarter,
    eighth_dot,
    eighth,
    sixteenth_dot,
    sixteenth,
    thirty_second,
};

inline constexpr int length_count = 10;

// Duration in quarter notes (beats): whole = 4 ... 32th = 0.125.
double beats(Length length);

// The document spelling: "whole", "half_dot", ..., "8th", "16th_dot", "16th", "32th".
std::string_view to_string(Length length);
std::optional<Length> parse_length(std::string_view text);

// All spellings joined by ", ", for error messages.
std::string_view length_spellings();

}  // namespace vibscore
