#include "daemon/render/fitting/actuator_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "actuator/physics.hpp"
#include "common/number_text.hpp"
#include "daemon/render/actuator_response.hpp"
#include "daemon/render/fitting/clef_check.hpp"

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
    // Every note whose number its clef's check calls out of reach on its string (the one rule,
    // render::out_of_reach): named each, with number, string and bar.
    std::set<std::pair<std::size_t, std::size_t>> unreachable;  // (bar, symbol), from 0
    std::vector<ActuatorWarning> out_of_reach_notes;
    for (std::size_t b = 0; b < bundle.score.bars.size(); ++b) {
        const Bar& bar = bundle.score.bars[b];
        const Clef& clef = bundle.clef_of(bar);
        for (std::size_t s = 0; s < bar.symbols.size(); ++s) {
            const auto* note = std::get_if<Note>(&bar.symbols[s]);
            if (note == nullptr || note->number < 1 || note->string < 1) {
                continue;
            }
            const auto number = static_cast<std::size_t>(note->number - 1);
            const auto string = static_cast<std::size_t>(note->string - 1);
            if (const auto full = out_of_reach(clef, number, string, declaration)) {
                unreachable.insert({b, s});
                out_of_reach_notes.push_back(
                    {b + 1, note_in_bar(bundle, b, s),
                     "number " + std::to_string(note->number) + " (strength " +
                         number_text(clef.numbers[number]) + ") out of reach on string " +
                         std::to_string(note->string) + " of clef " + bar.clef +
                         " (full drive gives at most " + two_places(*full) + " there)"});
            }
        }
    }
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
        // A note out of reach is named so above: "too short" would give the wrong reason.
        if (!(written > 0.0) || produced >= 0.9 * written ||
            unreachable.contains({tone.bar, tone.symbol})) {
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
    // In score order, each note's warnings together (its string's first).
    warnings.insert(warnings.end(), out_of_reach_notes.begin(), out_of_reach_notes.end());
    std::stable_sort(warnings.begin(), warnings.end(), [](const auto& a, const auto& b) {
        return std::pair(a.bar, a.note) < std::pair(b.bar, b.note);
    });
    return warnings;
}

}  // namespace vibscore::render
