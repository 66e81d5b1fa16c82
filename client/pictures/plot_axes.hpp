#pragma once

#include <cairo.h>

#include <functional>
#include <string>

// The frame of a plot of a quantity over time from 0, with round ticks on both axes and their
// labels: what the response picture (render --actuator) and the calibration picture share. The
// signal picture labels its value axis by the signal's peak instead, and draws its own.
namespace vibscore::pictures {

struct PlotAxes {
    double left = 0, top = 0, right = 0, bottom = 0;  // the frame, in pixels
    double span_s = 1.0;                              // the time axis: 0 .. span_s
    double top_value = 1.0;                           // the value axis: 0 .. top_value
    std::function<double(double)> x_of;               // seconds -> x
    std::function<double(double)> y_of;               // value -> y
    std::string value_label;                          // e.g. "strength (1 = the rated drive)"
};

// Draws the frame and the ticks (`frame`), and the tick labels and axis names (`labels`), in
// black, solid lines 1 px wide.
void draw_plot_axes(cairo_t* cairo, const PlotAxes& axes, bool frame, bool labels);

}  // namespace vibscore::pictures
