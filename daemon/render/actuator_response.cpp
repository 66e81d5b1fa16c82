#include "daemon/render/actuator_response.hpp"

#include <algorithm>
#include <cmath>

#include "actuator/timeline.hpp"
#include "daemon/render/cue_schedule.hpp"

namespace vibscore::render {

namespace {

// The drive a cue sets `dt` after its own time: its ramp moved on, if it has one.
actuator::Drive drive_of(const Cue& cue, double dt) {
    double amplitude = cue.amplitude;
    if (cue.ramp_s > 0.0) {
        amplitude += (cue.ramp_to - cue.amplitude) * std::min(1.0, dt / cue.ramp_s);
    }
    return {std::clamp(amplitude, -1.0, 1.0), cue.frequency_hz};
}

}  // namespace

std::vector<double> produced_strength(const actuator::Declaration& declaration,
                                      const std::vector<Cue>& drives, double rate_hz,
                                      std::size_t count, double step_s) {
    // The physics is stepped by actuator::Timeline, the sim backend's model too: this loop only
    // says which drive is in force when. Each boundary (a drive's time, a ramp's step, a sample)
    // is a command, so the state moves on from boundary to boundary.
    actuator::Timeline timeline(declaration);
    std::vector<double> strength;
    strength.reserve(count);
    std::size_t next = 0;
    const Cue* current = nullptr;
    double now = 0.0;
    // Moves to `t`, taking every drive on the way at its own time.
    const auto move_to = [&](double t) {
        while (now < t) {
            double until = t;
            if (next < drives.size() && drives[next].at < until) {
                until = std::max(now, drives[next].at);
            }
            if (current != nullptr && current->ramp_s > 0.0) {
                until = std::min(until, now + step_s);
            }
            now = until;
            while (next < drives.size() && drives[next].at <= now) {
                if (drives[next].kind == Cue::Kind::drive) {
                    current = &drives[next];
                }
                ++next;
            }
            if (current != nullptr) {
                timeline.command(now, drive_of(*current, now - current->at));
            }
        }
    };
    for (std::size_t k = 0; k < count; ++k) {
        move_to(static_cast<double>(k) / rate_hz);
        strength.push_back(timeline.response_at(now));
    }
    return strength;
}

ActuatorResponse actuator_response(const Performance& performance,
                                   const actuator::Declaration& declaration,
                                   const ResponseOptions& options) {
    ActuatorResponse response;
    response.rate_hz = options.rate_hz;
    const auto count = static_cast<std::size_t>(
        std::ceil((performance.duration() + options.tail_s) * options.rate_hz));
    for (std::size_t k = 0; k < count; ++k) {
        response.written.push_back(
            performance.envelope_at(static_cast<double>(k) / options.rate_hz) * options.scale);
    }
    const auto schedule = cue_schedule(performance);
    for (const bool compensation : {false, true}) {
        CueAdaptation adaptation;
        adaptation.frequency = options.frequency_control;
        adaptation.scale = options.scale;
        adaptation.actuator = declaration;
        adaptation.actuator->compensation = compensation;
        adaptation.reverse = options.reverse;
        auto drives = adapt_cues(schedule, performance.duration(), adaptation);
        std::erase_if(drives, [](const Cue& cue) { return cue.kind != Cue::Kind::drive; });
        auto strength = produced_strength(declaration, drives, options.rate_hz, count);
        (compensation ? response.compensated : response.uncompensated) = std::move(strength);
        (compensation ? response.compensated_drives : response.uncompensated_drives) =
            std::move(drives);
    }
    return response;
}

}  // namespace vibscore::render
