#pragma once

#include <cstddef>
#include <vector>

#include "score/clef.hpp"

namespace vibscore::render {

// One string of a curve or line clef: a level for every normalised time 0..1 of a quarter note.
// curve joins the points with a Catmull-Rom spline (cubic Hermite with tangents taken from the
// neighbouring points, scaled to the uneven spacing in time); line joins them with straight
// segments. Two points at the same time make a vertical step; each side of a step is its own
// spline. Before the first point and after the last the level holds.
class Waveform {
  public:
    Waveform(ClefType type, const std::vector<ClefPoint>& points);

    double level(double tau) const;

    // As level(), for a tau that mostly increases between calls: hint remembers the segment.
    double level(double tau, std::size_t& hint) const;

    // The times (0..1) of the control points, where a line waveform has its corners and steps.
    const std::vector<double>& point_times() const { return point_times_; }

  private:
    struct Segment {
        double start = 0.0;                             // tau where it begins
        double width = 0.0;                             // > 0
        double c0 = 0.0, c1 = 0.0, c2 = 0.0, c3 = 0.0;  // level = c0 + s(c1 + s(c2 + s c3))
    };

    double evaluate(const Segment& segment, double tau) const;

    std::vector<Segment> segments_;
    std::vector<double> point_times_;
    double first_level_ = 0.0;
    double last_level_ = 0.0;
};

}  // namespace vibscore::render
