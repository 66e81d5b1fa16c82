#include "daemon/render/actuator_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "common/number_text.hpp"
#include "daemon/actuator/physics.hpp"
#include "daemon/render/actuator_response.hpp"

namespace vibscore::render {

namespace {

constexpr double kRate = 4000.0;  // samples per second of the simulated strength

std::string two_places(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", value);
    return text;
}

std::string milliseconds(double seconds) {
    return number_text(std::round(seconds * 1000.0)) + " ms";
}

// The note's place among its bar's notes (1-based).
std::size_t note_in_bar(const ScoreBundle& bundle, std::size_t bar, std::size_t symbol) {
    std::size_t notes = 0;
    const auto& symbols = bundle.score.bars.at(bar).symbols;
    for (std::size_t s = 0; s <= symbol && s < symbols.size(); ++s) {
        notes += std::holds_alternative<Note>(symbols[s]) ? 1 : 0;
    }
    return notes;
}

const Note& note_of(const ScoreBundle& bundle, const Tone& tone) {
    return std::get<Note>(bundle.score.bars.at(tone.bar).symbols.at(tone.symbol));
}

}  // namespace

std::string describe(const ActuatorWarning& warning) {
    return "bar " + std::to_string(warning.bar) + ", note " + std::to_string(warning.note) + ": " +
           warning.text;
}

std::vector<ActuatorWarning> actuator_warnings(const ScoreBundle& bundle,
                                               const Performance& performance,
                                               const actuator::Declaration& declaration) {
    std::vector<ActuatorWarning> warnings;
    const actuator::Physics physics(declaration);
    ResponseOptions options;
    options.rate_hz = kRate;
    options.reverse = declaration.brake == actuator::Brake::reverse;
    const ActuatorResponse response = actuator_response(performance, declaration, options);
    const auto index = [&](double t) {
        return std::min(response.compensated.size(),
                        static_cast<std::size_t>(std::ceil(t * kRate - 1e-9)));
    };
    const bool lra = declaration.kind == actuator::Kind::lra;
    std::map<std::pair<const Clef*, int>, bool> strings_warned;
    for (const Tone& tone : performance.tones()) {
        const double asked = std::max(std::abs(tone.amplitude_start), std::abs(tone.amplitude_end));
        if (!(asked > 0.0)) {
            continue;
        }
        const ActuatorWarning at{tone.bar + 1, note_in_bar(bundle, tone.bar, tone.symbol), {}};
        const double frequency = tone.kind == Tone::Kind::sine ? tone.frequency_start : 0.0;
        if (lra && tone.kind == Tone::Kind::sine) {
            const Clef& clef = bundle.clef_of(bundle.score.bars.at(tone.bar));
            const int string = note_of(bundle, tone).string;
            const double full = physics.steady_strength({1.0, frequency});
            // The strongest this string is asked for anywhere in the score.
            double strongest = 0.0;
            for (const Tone& other : performance.tones()) {
                if (other.kind == Tone::Kind::sine && other.frequency_start == frequency) {
                    strongest = std::max({strongest, std::abs(other.amplitude_start),
                                          std::abs(other.amplitude_end)});
                }
            }
            if (full < 0.5 * strongest && !strings_warned[{&clef, string}]) {
                strings_warned[{&clef, string}] = true;
                ActuatorWarning warning = at;
                warning.text = "string " + std::to_string(string) + " (" + number_text(frequency) +
                               " Hz, clef " + bundle.score.bars.at(tone.bar).clef +
                               "): full drive gives strength " + two_places(full) +
                               " there, less than half the " + number_text(strongest) +
                               " the score asks on it (the actuator resonates at " +
                               number_text(declaration.resonance_hz) + " Hz)";
                warnings.push_back(std::move(warning));
            }
        }
        // The note's written peak (a shape's waveform scales its number) and the best it gets.
        double written = 0.0, produced = 0.0;
        for (std::size_t k = index(tone.onset); k < index(tone.end()); ++k) {
            written = std::max(written, response.written[k]);
            produced = std::max(produced, response.compensated[k]);
        }
        if (!(written > 0.0) || produced >= 0.9 * written) {
            continue;
        }
        const auto needed = physics.time_to({}, {1.0, frequency}, 0.9 * written, 10.0);
        ActuatorWarning warning = at;
        warning.text = "too short for the actuator: " + milliseconds(tone.duration) +
                       " at strength " + number_text(std::round(written * 1000.0) / 1000.0) +
                       " reaches " + two_places(produced) + " even with overdrive";
        if (needed.outcome == actuator::Physics::Reach::Outcome::reached) {
            warning.text += " (90 % takes " + milliseconds(needed.after_s) + " at full drive)";
        } else {
            warning.text += " (full drive never gives 90 % of it)";
        }
        warnings.push_back(std::move(warning));
    }
    return warnings;
}

}  // namespace vibscore::render
