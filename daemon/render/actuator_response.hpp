#pragma once

#include <vector>

#include "actuator/declaration.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/performance.hpp"

namespace vibscore::render {

// The strength a declared actuator produces when it is sent `drives` (drive cues as the player
// sends them: amplitude -1..1 of full scale; a ramp followed in steps of `step_s`), sampled at
// `rate_hz` from time 0 for `count` samples. Exact between drives: actuator::Timeline steps the
// physics, as it does for the sim backend.
std::vector<double> produced_strength(const actuator::Declaration& declaration,
                                      const std::vector<Cue>& drives, double rate_hz,
                                      std::size_t count, double step_s = 0.005);

struct ResponseOptions {
    double rate_hz = 1000.0;
    // How long after the score's end to keep looking: the ringing of its last note.
    double tail_s = 0.3;
    // What the backend can do, as the player would adapt to it.
    bool frequency_control = true;
    bool reverse = true;
    double scale = 1.0;  // the playback's intensity
};

// What a declared actuator makes of a score, with and without compensation (`vibscore render
// --actuator`, bench/feel): the written strength (the score's envelope x scale, in strength units
// where 1 is the rated drive) and the strength the actuator produces from the drives the renderer
// sends it either way, all sampled alike.
struct ActuatorResponse {
    double rate_hz = 0.0;
    std::vector<double> written;
    std::vector<double> uncompensated;
    std::vector<double> compensated;
    std::vector<Cue> uncompensated_drives;
    std::vector<Cue> compensated_drives;
};
ActuatorResponse actuator_response(const Performance& performance,
                                   const actuator::Declaration& declaration,
                                   const ResponseOptions& options = {});

}  // namespace vibscore::render
