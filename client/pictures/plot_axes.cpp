#include "client/pictures/plot_axes.hpp"

#include <cmath>

#include "client/pictures/axis_ticks.hpp"
#include "client/pictures/picture_text.hpp"

namespace vibscore::pictures {

void draw_plot_axes(cairo_t* cairo, const PlotAxes& axes, bool frame, bool labels) {
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_line_width(cairo, 1.0);
    cairo_set_dash(cairo, nullptr, 0, 0);
    if (frame) {
        cairo_rectangle(cairo, axes.left + 0.5, axes.top + 0.5, axes.right - axes.left,
                        axes.bottom - axes.top);
        cairo_stroke(cairo);
    }
    select_font(cairo, 10, false);
    const double step = tick_step(axes.span_s, 10);
    for (double t = 0.0; t <= axes.span_s + step * 1e-6; t += step) {
        const double x = std::round(axes.x_of(t)) + 0.5;
        if (frame) {
            cairo_move_to(cairo, x, axes.bottom);
            cairo_line_to(cairo, x, axes.bottom + 5);
            cairo_stroke(cairo);
        }
        if (labels) {
            const auto label = tick_label(t, step);
            show_text_at(cairo, x - text_width(cairo, label) / 2, axes.bottom + 17, label);
        }
    }
    const double value_step = tick_step(axes.top_value, 4);
    for (double v = 0.0; v <= axes.top_value + value_step * 1e-6; v += value_step) {
        const double y = std::round(axes.y_of(v)) + 0.5;
        if (frame) {
            cairo_move_to(cairo, axes.left - 5, y);
            cairo_line_to(cairo, axes.left, y);
            cairo_stroke(cairo);
        }
        if (labels) {
            const auto label = tick_label(v, value_step);
            // Right-aligned against the ticks, however long the number.
            show_text_at(cairo, axes.left - 8 - text_width(cairo, label), y + 4, label);
        }
    }
    if (labels) {
        show_text_at(cairo, axes.right - 40, axes.bottom + 33, "t (s)");
        show_text_at(cairo, axes.left, axes.bottom + 33, axes.value_label);
    }
}

}  // namespace vibscore::pictures
