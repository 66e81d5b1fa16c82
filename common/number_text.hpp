#pragma once

#include <string>

namespace vibscore {

// A number as a person writes it: the shortest decimal that reads back as the same double
// ("1000", "0.25", "3600000"), never "1000.000000" or "3.6e+06".
std::string number_text(double value);

}  // namespace vibscore
