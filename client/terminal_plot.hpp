#pragma once

#include <ostream>

#include "daemon/render/performance.hpp"

namespace vibscore::client {

// Draws the performance's strength over time as a bar chart `width` columns wide and `height`
// rows high, with a time axis, so a person can see a pattern without an actuator.
void plot_envelope(std::ostream& out, const render::Performance& performance, int width,
                   int height);

}  // namespace vibscore::client
