#pragma once

#include <cairo.h>

#include <string>

// How the lines of a plot are told apart where they run together (solid, thin, dashed, each its
// ink), and the legend entry that shows one: what the response and calibration pictures share.
namespace vibscore::pictures {

struct TraceStroke {
    const double* ink;  // r, g, b
    double width = 1.8;
    double dash_on = 0.0, dash_off = 0.0;  // px; 0 on: solid
};

// Sets the source, the width and the dash for the next stroke.
void apply_stroke(cairo_t* cairo, const TraceStroke& stroke);

// The legend's sample line, 20 px long and 4.5 px above `baseline`, and its label 5 px after.
inline constexpr double kLegendLine = 20.0;
double legend_entry_width(cairo_t* cairo, const std::string& label);
void draw_legend_entry(cairo_t* cairo, double x, double baseline, const std::string& label,
                       const TraceStroke& stroke, bool line, bool text);

}  // namespace vibscore::pictures
