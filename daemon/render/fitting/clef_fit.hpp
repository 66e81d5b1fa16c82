#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "actuator/declaration.hpp"
#include "score/clef.hpp"

// A written clef fitted to a declared actuator (`vibscore clef fit`, `[clefs] fit = auto`): the
// score keeps its meaning (which string, which number, its tempo) and the actuator gets what it
// can play at full strength. docs/clefs.md gives the rules with their numbers; every constant
// here is one of them.
namespace vibscore::render {

// Neighbouring strings at least this frequency ratio apart are felt as different pitches.
inline constexpr double kDistinctPitchRatio = 1.2;
// Where skin feels pitch at all (Pacinian range): a fitted string stays inside it.
inline constexpr double kLowestPitchHz = 40.0;
inline constexpr double kHighestPitchHz = 400.0;
// Thesis Fig. 5.2b: the vibration motor's strings as square-wave modulation, 120 ms for string 1
// down to 20 ms for string 6, in equal steps.
inline constexpr double kRoughestPeriodS = 0.120;
inline constexpr double kSmoothestPeriodS = 0.020;
// Without compensation the renderer drives number x rated-drive whatever the frequency: a string
// is placed only where that still gives this share of the number's strength.
inline constexpr double kUncompensatedGain = 0.9;

// How vibscored names a clef it fitted to the actuator (BarClefs, vibscore info NAME):
// "lra-phone (fitted)".
inline constexpr std::string_view kFittedMark = " (fitted)";

// A clef the fit cannot write (a roughness string needing more points than a string may hold).
class ClefFitError : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

// Where an LRA gives at least `strength` (strength units, 1 = rated drive at resonance) at full
// drive, within kLowestPitchHz..kHighestPitchHz; nothing when it gives that nowhere (or for an
// ERM, which has no pitch to place).
struct Band {
    double low_hz = 0.0, high_hz = 0.0;
};
std::optional<Band> full_strength_band(const actuator::Declaration& declaration, double strength);

// How long the actuator takes from rest to `strength` under the drive compensation gives it (full
// scale; with compensation off, rated drive and 90 % of the strength). Infinity when out of reach.
double time_to_strength_s(const actuator::Declaration& declaration, double strength);

// The shortest rise or fall of a shape the actuator follows: the time it takes to travel half of
// the clef's strongest strength.
double shortest_followed_s(const actuator::Declaration& declaration, double strongest);

// The roughness periods of `strings` strings (string 1 first): the thesis' periods, 120 ms down to
// 20 ms in equal steps, each lengthened where needed so the actuator reaches `strongest` in half a
// period and neighbours stay kDistinctPitchRatio apart. One string: none (a steady level).
std::vector<double> roughness_periods_s(const actuator::Declaration& declaration,
                                        std::size_t strings, double strongest);

// The shortest rise or fall of a wiggle in a shape string (a ramp up straight into a ramp down or
// the reverse, steps left out: a step is deliberate on/off drive), in normalised time; nothing when
// the string has none.
std::optional<double> shortest_wiggle(const ClefString& string);

struct ClefFit {
    enum class Strings { as_written, pitch, roughness, smoothed };
    Clef clef;  // the device clef
    Strings strings = Strings::as_written;
    std::optional<Band> band;            // sine clefs on an LRA: where full strength is
    std::vector<double> frequencies_hz;  // pitch: each fitted string's frequency
    std::vector<double> periods_s;       // roughness: each string's period (empty: one string)
    std::vector<std::string> notes;      // what the fit changed and why, one line each
    bool changed() const { return !notes.empty(); }
};

// The rules (docs/clefs.md):
//  - sine clef, LRA: strings already inside the full-strength band and kDistinctPitchRatio apart
//    stay; otherwise they are spread geometrically across the band in their written order when it
//    holds them kDistinctPitchRatio apart; otherwise (and always on an ERM) they become roughness:
//    a line clef of 50 % square waves (roughness_periods_s) that the actuator plays at its own
//    frequency;
//  - numbers keep their strengths; one beyond what full drive gives anywhere becomes that;
//  - curve and line clefs keep their shapes; a string with a wiggle shorter than
//    shortest_followed_s is smoothed over that time.
// Throws ClefFitError when the result cannot be written as a clef.
ClefFit fit_clef(const Clef& written, const actuator::Declaration& declaration);

std::string_view to_string(ClefFit::Strings strings);

}  // namespace vibscore::render
