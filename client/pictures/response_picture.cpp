#include "client/pictures/response_picture.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "client/pictures/axis_ticks.hpp"
#include "client/pictures/picture_text.hpp"

namespace vibscore::pictures {

namespace {

// The plot's frame inside the picture; above it, the title and legend, then the caption.
constexpr double kLeft = 58.0, kRight = 16.0, kTop = 50.0, kBottom = 42.0;
constexpr double kTitleBaseline = 20.0, kCaptionBaseline = 38.0;
constexpr double kLegendLine = 20.0, kLegendGap = 16.0;

struct Trace {
    ResponsePicture::Layer layer;
    const double* ink;
    const char* label;
};

constexpr Trace kTraces[] = {
    {ResponsePicture::written, ResponsePicture::written_ink, "written"},
    {ResponsePicture::uncompensated, ResponsePicture::uncompensated_ink, "actuator, uncompensated"},
    {ResponsePicture::compensated, ResponsePicture::compensated_ink, "actuator, compensated"},
};

// How each trace is stroked, so that they stay apart where they run together: the written one
// thin over a light fill, the uncompensated dashed, the compensated solid and widest.
void stroke_style(cairo_t* cairo, ResponsePicture::Layer layer) {
    static const double dashes[] = {6.0, 3.0};
    cairo_set_dash(cairo, nullptr, 0, 0);
    switch (layer) {
        case ResponsePicture::written:
            cairo_set_line_width(cairo, 1.2);
            break;
        case ResponsePicture::uncompensated:
            cairo_set_line_width(cairo, 1.6);
            cairo_set_dash(cairo, dashes, 2, 0);
            break;
        default:
            cairo_set_line_width(cairo, 1.8);
            break;
    }
}

double largest(const std::vector<double>& values) {
    double peak = 0.0;
    for (const double value : values) {
        peak = std::max(peak, std::abs(value));
    }
    return peak;
}

}  // namespace

ResponsePicture::ResponsePicture(const render::Performance& performance,
                                 render::ActuatorResponse response, std::string title,
                                 std::string caption, const Options& options)
    : performance_(performance),
      response_(std::move(response)),
      title_(std::move(title)),
      caption_(std::move(caption)),
      options_(options) {
    const double peak = std::max({largest(response_.written), largest(response_.uncompensated),
                                  largest(response_.compensated)});
    top_ = peak > 0.0 ? peak * 1.08 : 1.0;
    if (response_.rate_hz > 0.0 && !response_.written.empty()) {
        span_ = static_cast<double>(response_.written.size()) / response_.rate_hz;
    }
    span_ = std::max({span_, performance_.duration(), 1e-3});
}

double ResponsePicture::x_of(double t) const {
    return kLeft + t / span_ * (options_.width - kLeft - kRight);
}

double ResponsePicture::y_of(double strength) const {
    const double bottom = options_.height - kBottom;
    return bottom - strength / top_ * (bottom - kTop);
}

void ResponsePicture::draw(cairo_t* cairo, Layers layers) const {
    draw_header(cairo, layers);
    draw_boundaries(cairo, layers);
    draw_traces(cairo, layers);
    draw_axes(cairo, layers);
}

void ResponsePicture::draw_header(cairo_t* cairo, Layers layers) const {
    const double right = options_.width - kRight;
    // The legend's entries from the right edge leftwards, each as wide as its text.
    select_font(cairo, 10, false);
    std::vector<double> entry_x(std::size(kTraces));
    double x = right;
    for (std::size_t i = std::size(kTraces); i-- > 0;) {
        x -= kLegendLine + 5 + text_width(cairo, kTraces[i].label);
        entry_x[i] = x;
        x -= kLegendGap;
    }
    const double legend_left = x;
    for (std::size_t i = 0; i < std::size(kTraces); ++i) {
        const Trace& trace = kTraces[i];
        if (layers & legend) {
            cairo_set_source_rgb(cairo, trace.ink[0], trace.ink[1], trace.ink[2]);
            stroke_style(cairo, trace.layer);
            cairo_move_to(cairo, std::round(entry_x[i]), kLegendLine - 4.5);
            cairo_line_to(cairo, std::round(entry_x[i]) + kLegendLine, kLegendLine - 4.5);
            cairo_stroke(cairo);
            cairo_set_dash(cairo, nullptr, 0, 0);
        }
        if (layers & legend_text) {
            select_font(cairo, 10, false);
            cairo_set_source_rgb(cairo, 0, 0, 0);
            show_text_at(cairo, entry_x[i] + kLegendLine + 5, kTitleBaseline, trace.label);
        }
    }
    if (layers & title) {
        cairo_set_source_rgb(cairo, 0, 0, 0);
        select_font(cairo, 14, true);
        // A long title is cut short before the legend.
        show_text_at(cairo, kLeft, kTitleBaseline,
                     elided_text(cairo, title_, legend_left - 12 - kLeft));
    }
    if (layers & caption) {
        cairo_set_source_rgb(cairo, 0.3, 0.3, 0.3);
        select_font(cairo, 10, false);
        show_text_at(cairo, kLeft, kCaptionBaseline, elided_text(cairo, caption_, right - kLeft));
    }
}

void ResponsePicture::draw_axes(cairo_t* cairo, Layers layers) const {
    const double bottom = options_.height - kBottom;
    const double right = options_.width - kRight;
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_line_width(cairo, 1.0);
    cairo_set_dash(cairo, nullptr, 0, 0);
    if (layers & frame) {
        cairo_rectangle(cairo, kLeft + 0.5, kTop + 0.5, right - kLeft, bottom - kTop);
        cairo_stroke(cairo);
    }
    select_font(cairo, 10, false);
    const double step = tick_step(span_, 10);
    for (double t = 0.0; t <= span_ + step * 1e-6; t += step) {
        const double x = std::round(x_of(t)) + 0.5;
        if (layers & frame) {
            cairo_move_to(cairo, x, bottom);
            cairo_line_to(cairo, x, bottom + 5);
            cairo_stroke(cairo);
        }
        if (layers & axis_labels) {
            const auto label = tick_label(t, step);
            show_text_at(cairo, x - text_width(cairo, label) / 2, bottom + 17, label);
        }
    }
    const double strength_step = tick_step(top_, 4);
    for (double s = 0.0; s <= top_ + strength_step * 1e-6; s += strength_step) {
        const double y = std::round(y_of(s)) + 0.5;
        if (layers & frame) {
            cairo_move_to(cairo, kLeft - 5, y);
            cairo_line_to(cairo, kLeft, y);
            cairo_stroke(cairo);
        }
        if (layers & axis_labels) {
            const auto label = tick_label(s, strength_step);
            // Right-aligned against the ticks, however long the number.
            show_text_at(cairo, kLeft - 8 - text_width(cairo, label), y + 4, label);
        }
    }
    if (layers & axis_labels) {
        show_text_at(cairo, right - 40, bottom + 33, "t (s)");
        show_text_at(cairo, kLeft, bottom + 33, "strength (1 = the rated drive)");
    }
}

void ResponsePicture::draw_boundaries(cairo_t* cairo, Layers layers) const {
    if (!(layers & bar_boundaries)) {
        return;
    }
    const double bottom = options_.height - kBottom;
    const double dashes[] = {4.0, 3.0};
    cairo_set_dash(cairo, dashes, 2, 0);
    cairo_set_line_width(cairo, 1.0);
    const auto line_at = [&](double t) {
        const double x = std::round(x_of(t)) + 0.5;
        cairo_move_to(cairo, x, kTop);
        cairo_line_to(cairo, x, bottom);
        cairo_stroke(cairo);
    };
    cairo_set_source_rgb(cairo, 0.7, 0.7, 0.7);
    std::size_t bar = static_cast<std::size_t>(-1);
    for (const auto& timing : performance_.timeline()) {
        if (timing.bar != bar && timing.onset > 0.0) {
            line_at(timing.onset);
        }
        bar = timing.bar;
    }
    // The score's end, after which the actuator only rings out.
    cairo_set_source_rgb(cairo, 0.3, 0.3, 0.3);
    line_at(performance_.duration());
    cairo_set_dash(cairo, nullptr, 0, 0);
}

void ResponsePicture::draw_traces(cairo_t* cairo, Layers layers) const {
    if (response_.rate_hz <= 0.0) {
        return;
    }
    const auto path = [&](const std::vector<double>& values) {
        for (std::size_t k = 0; k < values.size(); ++k) {
            const double x = x_of(static_cast<double>(k) / response_.rate_hz);
            const double y = y_of(values[k]);
            k == 0 ? cairo_move_to(cairo, x, y) : cairo_line_to(cairo, x, y);
        }
    };
    cairo_set_line_join(cairo, CAIRO_LINE_JOIN_BEVEL);
    for (const Trace& trace : kTraces) {
        const auto& values = trace.layer == written         ? response_.written
                             : trace.layer == uncompensated ? response_.uncompensated
                                                            : response_.compensated;
        if (!(layers & trace.layer) || values.empty()) {
            continue;
        }
        if (trace.layer == written) {
            // The written strength as an area, so the produced ones read against it.
            path(values);
            cairo_line_to(cairo, x_of(static_cast<double>(values.size() - 1) / response_.rate_hz),
                          y_of(0.0));
            cairo_line_to(cairo, x_of(0.0), y_of(0.0));
            cairo_close_path(cairo);
            cairo_set_source_rgb(cairo, 0.9, 0.9, 0.9);
            cairo_fill(cairo);
        }
        cairo_set_source_rgb(cairo, trace.ink[0], trace.ink[1], trace.ink[2]);
        stroke_style(cairo, trace.layer);
        path(values);
        cairo_stroke(cairo);
    }
    cairo_set_dash(cairo, nullptr, 0, 0);
}

}  // namespace vibscore::pictures
