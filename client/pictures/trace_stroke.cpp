#include "client/pictures/trace_stroke.hpp"

#include <cmath>

#include "client/pictures/picture_text.hpp"

namespace vibscore::pictures {

void apply_stroke(cairo_t* cairo, const TraceStroke& stroke) {
    cairo_set_source_rgb(cairo, stroke.ink[0], stroke.ink[1], stroke.ink[2]);
    cairo_set_line_width(cairo, stroke.width);
    if (stroke.dash_on > 0.0) {
        const double dashes[] = {stroke.dash_on, stroke.dash_off};
        cairo_set_dash(cairo, dashes, 2, 0);
    } else {
        cairo_set_dash(cairo, nullptr, 0, 0);
    }
}

double legend_entry_width(cairo_t* cairo, const std::string& label) {
    select_font(cairo, 10, false);
    return kLegendLine + 5 + text_width(cairo, label);
}

void draw_legend_entry(cairo_t* cairo, double x, double baseline, const std::string& label,
                       const TraceStroke& stroke, bool line, bool text) {
    if (line) {
        apply_stroke(cairo, stroke);
        cairo_move_to(cairo, std::round(x), baseline - 4.5);
        cairo_line_to(cairo, std::round(x) + kLegendLine, baseline - 4.5);
        cairo_stroke(cairo);
        cairo_set_dash(cairo, nullptr, 0, 0);
    }
    if (text) {
        select_font(cairo, 10, false);
        cairo_set_source_rgb(cairo, 0, 0, 0);
        show_text_at(cairo, x + kLegendLine + 5, baseline, label);
    }
}

}  // namespace vibscore::pictures
