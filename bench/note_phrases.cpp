#include "bench/note_phrases.hpp"

#include <algorithm>
#include <cmath>

#include "bench/feel_plant.hpp"

namespace vibscore::bench {

Played play_notes(const actuator::Declaration& declared, const actuator::Declaration& truth,
                  const render::PlannerOptions& options, const Notes& notes, double length) {
    render::DrivePlanner planner(declared, options);
    Played played;
    double at = 0.0;
    for (std::size_t i = 0; i < notes.size(); ++i) {
        planner.segment(at, at + length, notes[i].first, notes[i].second, true, played.drives);
        const bool last = i + 1 == notes.size();
        planner.segment(at + length, last ? INFINITY : at + 2.0 * length, 0.0, 0.0, false,
                        played.drives);
        at += 2.0 * length;
    }
    played.strength = Plant(truth).respond(played.drives, kPhraseRate,
                                           static_cast<std::size_t>((at + 0.2) * kPhraseRate));
    return played;
}

Artefacts artefacts(const Played& played, const Notes& notes, double length) {
    Artefacts worst;
    for (std::size_t i = 0; i < notes.size(); ++i) {
        const double strength = notes[i].first;
        const auto from = static_cast<std::size_t>(2.0 * length * i * kPhraseRate);
        const auto end = static_cast<std::size_t>((2.0 * i + 1.0) * length * kPhraseRate);
        const auto next =
            std::min(played.strength.size(),
                     static_cast<std::size_t>((2.0 * i + 2.0) * length * kPhraseRate));
        for (std::size_t k = from; k < end; ++k) {
            worst.overshoot = std::max(worst.overshoot, played.strength[k] / strength - 1.0);
        }
        std::size_t k = end;
        while (k < next && played.strength[k] >= 0.1 * strength) {
            ++k;
        }
        for (; k < next; ++k) {
            worst.rebound = std::max(worst.rebound, played.strength[k] / strength);
        }
    }
    return worst;
}

}  // namespace vibscore::bench
