#pragma once

#include <string>

namespace vibscore {

// A number as a person writes it: the shortest decimal that reads back as the same double
// ("1000", "0.25", "3600000"), never "1000.000000" or "3.6e+06".
std::string number_text(double value);

// A measured or computed value as a person reads it: at most `significant` digits, trailing
// zeros dropped ("0.428571" for 3/7, "0.2", "140"); large values as number_text writes them.
std::string rounded_text(double value, int significant = 6);

// `value` to `places` decimals, trailing zeros dropped ("96.6", "1.2", "175"), as a message
// rounds a figure it shows.
std::string fixed_text(double value, int places);

// A frequency and a duration as messages write them, to a tenth: "175 Hz", "96.6 Hz"; "40 ms",
// "37.4 ms" (from seconds).
std::string hz_text(double hz);
std::string ms_text(double seconds);

}  // namespace vibscore
