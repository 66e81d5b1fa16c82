#pragma once

#include <limits>

namespace vibscore {

// What "a number above 0" means for a setting (vibscored.conf's [daemon] and [actuator], an
// actuator file): at least the smallest normal double, 2.2250738585072014e-308. A subnormal such
// as 5e-324 is above 0 too, but it has lost its precision and its reciprocal is infinite, so a
// model built on it (a strength divided by rated-drive) turns into infinity and NaN. One rule,
// so the config reader and the declaration parser refuse the same values.
inline constexpr double kSmallestAboveZero = std::numeric_limits<double>::min();

inline bool above_zero(double value) {
    return value >= kSmallestAboveZero;
}

}  // namespace vibscore
