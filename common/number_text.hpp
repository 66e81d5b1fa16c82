#pragma once

#include <string>

namespace vibscore {

// A number as a person writes it: the shortest decimal that reads back as the same double
// ("1000", "0.25", "3600000"), never "1000.000000" or "3.6e+06".
std::string number_text(double value);

// A measured or computed value as a person reads it: at most `significant` digits, trailing
// zeros dropped ("0.428571" for 3/7, "0.2", "140"); large values as number_text writes them.
std::string rounded_text(double value, int significant = 6);

}  // namespace vibscore
