#pragma once

#include <string>
#include <vector>

namespace vibscore {

// sine: each string is a frequency; curve/line: each string is a waveform over one quarter note
// given by control points, joined by a Catmull-Rom spline (curve) or straight segments (line).
enum class ClefType { sine, curve, line };

struct ClefPoint {
    double time = 0.0;   // normalised 0..1 over one quarter note
    double level = 0.0;  // normalised amplitude 0..1
    bool operator==(const ClefPoint&) const = default;
};

struct ClefString {
    double frequency = 0.0;         // Hz, sine clefs only
    std::vector<ClefPoint> points;  // curve and line clefs only, in time order
    bool operator==(const ClefString&) const = default;
};

struct Clef {
    ClefType type = ClefType::sine;
    std::string version = "1.0";
    double tempo = 1.0;               // seconds per quarter note
    std::vector<double> numbers;      // amplitude of number 1, 2, ...
    std::vector<ClefString> strings;  // string 1 (lowest pitch), 2, ...

    bool operator==(const Clef&) const = default;
};

std::string_view to_string(ClefType type);

}  // namespace vibscore
