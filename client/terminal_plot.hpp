#pragma once

#include <ostream>

#include "daemon/render/actuator_response.hpp"
#include "daemon/render/performance.hpp"

namespace vibscore::client {

// Draws the performance's strength over time as a bar chart `width` columns wide and `height`
// rows high, with a time axis, so a person can see a pattern without an actuator.
void plot_envelope(std::ostream& out, const render::Performance& performance, int width,
                   int height);

// What a declared actuator makes of a score (render --actuator --plot): three charts over one
// time axis, each `width` columns wide and `height` rows high and on one scale, so they compare
// row by row: the written strength, and the strength the actuator produces without and with
// compensation. Each column shows the largest strength within it.
void plot_response(std::ostream& out, const render::ActuatorResponse& response, int width,
                   int height);

}  // namespace vibscore::client
