#include "daemon/render/fitting/clef_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "actuator/physics.hpp"
#include "common/number_text.hpp"
#include "daemon/render/fitting/clef_fit.hpp"

namespace vibscore::render {

namespace {

std::string two_places(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", value);
    return text;
}

double strongest_of(const Clef& clef) {
    return clef.numbers.empty() ? 0.0 : *std::max_element(clef.numbers.begin(), clef.numbers.end());
}

// The shortest on-pulse of a shape string: from a step up to the next step down.
std::optional<double> shortest_pulse(const ClefString& string) {
    std::optional<double> shortest;
    double rose_at = -1.0;  // none yet
    const auto& points = string.points;
    for (std::size_t p = 1; p < points.size(); ++p) {
        if (points[p].time != points[p - 1].time) {
            continue;
        }
        if (points[p].level > points[p - 1].level) {
            rose_at = points[p].time;
        } else if (points[p].level < points[p - 1].level && rose_at >= 0.0) {
            const double pulse = points[p].time - rose_at;
            shortest = shortest ? std::min(*shortest, pulse) : pulse;
            rose_at = -1.0;
        }
    }
    // A string that starts high holds its first pulse from time 0.
    if (!points.empty() && points.front().level > 0.0) {
        for (std::size_t p = 1; p < points.size(); ++p) {
            if (points[p].time == points[p - 1].time && points[p].level < points[p - 1].level) {
                const double pulse = points[p].time - points.front().time;
                shortest = shortest ? std::min(*shortest, pulse) : pulse;
                break;
            }
        }
    }
    return shortest;
}

void check_sine(const Clef& clef, const actuator::Declaration& declaration,
                const actuator::Physics& physics, std::vector<std::string>& warnings) {
    const double strongest = strongest_of(clef);
    if (declaration.kind == actuator::Kind::erm) {
        if (clef.strings.size() > 1) {
            warnings.push_back("strings 1-" + std::to_string(clef.strings.size()) + " (" +
                               hz_text(clef.strings.front().frequency) + " to " +
                               hz_text(clef.strings.back().frequency) +
                               "): an ERM has no pitch, they all feel alike (vibscore clef fit "
                               "makes them roughness)");
        }
        return;
    }
    for (std::size_t s = 0; s < clef.strings.size(); ++s) {
        const double f = clef.strings[s].frequency;
        const double full = physics.steady_strength({1.0, f});
        if (full < strongest) {
            warnings.push_back("string " + std::to_string(s + 1) + " (" + hz_text(f) +
                               "): full drive gives strength " + two_places(full) +
                               ", less than the clef's strongest number (" +
                               number_text(strongest) + "); the LRA resonates at " +
                               hz_text(declaration.resonance_hz));
        }
        if (s > 0) {
            const double a = clef.strings[s - 1].frequency;
            const double ratio = std::max(a, f) / std::min(a, f);
            if (ratio < kDistinctPitchRatio) {
                warnings.push_back("strings " + std::to_string(s) + " and " +
                                   std::to_string(s + 1) + " (" + hz_text(a) + ", " + hz_text(f) +
                                   "): frequency ratio " + two_places(ratio) +
                                   ", closer than a person tells apart (" +
                                   number_text(kDistinctPitchRatio) + ")");
            }
        }
    }
    for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
        std::string strings;
        double best = 0.0;
        for (std::size_t s = 0; s < clef.strings.size(); ++s) {
            if (const auto full = out_of_reach(clef, n, s, declaration)) {
                strings += (strings.empty() ? "" : ", ") + std::to_string(s + 1);
                best = std::max(best, *full);
            }
        }
        if (!strings.empty()) {
            warnings.push_back("number " + std::to_string(n + 1) + " (strength " +
                               number_text(clef.numbers[n]) + "): out of reach on string" +
                               (strings.find(',') != std::string::npos ? "s " : " ") + strings +
                               " (full drive gives at most " + two_places(best) + " there)");
        }
    }
}

void check_shape(const Clef& clef, const actuator::Declaration& declaration,
                 const actuator::Physics& physics, std::vector<std::string>& warnings) {
    const double strongest = strongest_of(clef);
    const double reachable = physics.steady_strength({1.0, 0.0});
    for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
        if (!clef.strings.empty() && out_of_reach(clef, n, 0, declaration)) {
            warnings.push_back("number " + std::to_string(n + 1) + " (strength " +
                               number_text(clef.numbers[n]) + "): out of reach, full drive gives " +
                               two_places(reachable));
        }
    }
    const double follows = shortest_followed_s(declaration, strongest);
    const double reach = time_to_strength_s(declaration, std::min(strongest, reachable));
    const double drive = declaration.compensation ? 1.0 : declaration.rated_drive;
    for (std::size_t s = 0; s < clef.strings.size(); ++s) {
        const auto& string = clef.strings[s];
        if (const auto wiggle = shortest_wiggle(string); wiggle && *wiggle * clef.tempo < follows) {
            warnings.push_back("string " + std::to_string(s + 1) + ": a " +
                               ms_text(*wiggle * clef.tempo) + " rise or fall, faster than the " +
                               (declaration.kind == actuator::Kind::lra ? "LRA" : "ERM") +
                               " follows (" + ms_text(follows) + ")");
        }
        if (const auto pulse = shortest_pulse(string);
            pulse && *pulse * clef.tempo < reach * (1.0 - 1e-9)) {
            const double seconds = *pulse * clef.tempo;
            const double got =
                actuator::Physics::strength(physics.advance({}, {drive, 0.0}, seconds));
            warnings.push_back("string " + std::to_string(s + 1) + ": " + ms_text(seconds) +
                               " pulses reach strength " + two_places(got) + " of " +
                               number_text(strongest) + " (it takes " + ms_text(reach) + ")");
        }
    }
}

}  // namespace

std::optional<double> out_of_reach(const Clef& clef, std::size_t number, std::size_t string,
                                   const actuator::Declaration& declaration) {
    if (number >= clef.numbers.size() || string >= clef.strings.size()) {
        return std::nullopt;
    }
    const bool sine = clef.type == ClefType::sine;
    if (sine && declaration.kind == actuator::Kind::erm) {
        return std::nullopt;
    }
    // A shape plays at the actuator's own frequency (0 asks for it), whichever string.
    const double frequency = sine ? clef.strings[string].frequency : 0.0;
    const double full = actuator::Physics(declaration).steady_strength({1.0, frequency});
    if (full < clef.numbers[number]) {
        return full;
    }
    return std::nullopt;
}

std::vector<std::string> clef_warnings(const Clef& clef, const actuator::Declaration& declaration) {
    const actuator::Physics physics(declaration);
    std::vector<std::string> warnings;
    if (clef.type == ClefType::sine) {
        check_sine(clef, declaration, physics, warnings);
    } else {
        check_shape(clef, declaration, physics, warnings);
    }
    return warnings;
}

}  // namespace vibscore::render
