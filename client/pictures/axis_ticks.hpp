#pragma once

#include <string>

// Ticks on a plot's axes: round steps and their labels.
namespace vibscore::pictures {

// A round step for about `count` ticks over `span` (> 0): 1, 2 or 5 times a power of ten.
double tick_step(double span, int count);

// `value` with as many decimals as a tick `step` needs ("0.25" at 0.05, "2" at 1).
std::string tick_label(double value, double step);

}  // namespace vibscore::pictures
