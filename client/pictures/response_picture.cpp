#include "client/pictures/response_picture.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "client/pictures/picture_text.hpp"
#include "client/pictures/plot_axes.hpp"
#include "client/pictures/trace_stroke.hpp"

namespace vibscore::pictures {

namespace {

// The plot's frame inside the picture; above it the title, the caption's lines, the legend and
// the bar labels, each on a row of its own.
constexpr double kLeft = 58.0, kRight = 16.0, kBottom = 42.0;
constexpr double kTitleBaseline = 20.0, kCaptionBaseline = 38.0, kRow = 15.0;
constexpr double kLegendGap = 16.0;
constexpr double kBarLabelRow = 18.0, kAbovePlot = 6.0;

constexpr double kBoundaryDashes[] = {4.0, 3.0};

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t from = 0;
    for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', from)) {
        lines.push_back(text.substr(from, at - from));
        from = at + 1;
    }
    lines.push_back(text.substr(from));
    return lines;
}

struct Trace {
    ResponsePicture::Layer layer;
    TraceStroke stroke;
    const char* label;
};

// The written one thin over a light fill, the uncompensated dashed, the compensated solid and
// widest: they stay apart where they run together.
constexpr Trace kTraces[] = {
    {ResponsePicture::written, {ResponsePicture::written_ink, 1.2}, "written"},
    {ResponsePicture::uncompensated,
     {ResponsePicture::uncompensated_ink, 1.6, 6.0, 3.0},
     "actuator, uncompensated"},
    {ResponsePicture::compensated,
     {ResponsePicture::compensated_ink, 1.8},
     "actuator, compensated"},
};

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
      caption_(lines_of(caption)),
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

double ResponsePicture::plot_top() const {
    const double legend = kCaptionBaseline + static_cast<double>(caption_.size()) * kRow + 4;
    return legend + kBarLabelRow + kAbovePlot;
}

double ResponsePicture::y_of(double strength) const {
    const double bottom = options_.height - kBottom;
    return bottom - strength / top_ * (bottom - plot_top());
}

void ResponsePicture::draw(cairo_t* cairo, Layers layers) const {
    draw_header(cairo, layers);
    draw_bar_labels(cairo, layers);
    draw_boundaries(cairo, layers);
    draw_traces(cairo, layers);
    draw_axes(cairo, layers);
}

void ResponsePicture::draw_header(cairo_t* cairo, Layers layers) const {
    const double right = options_.width - kRight;
    if (layers & title) {
        cairo_set_source_rgb(cairo, 0, 0, 0);
        select_font(cairo, 14, true);
        show_text_at(cairo, kLeft, kTitleBaseline, elided_text(cairo, title_, right - kLeft));
    }
    if (layers & caption) {
        cairo_set_source_rgb(cairo, 0.3, 0.3, 0.3);
        select_font(cairo, 10, false);
        for (std::size_t i = 0; i < caption_.size(); ++i) {
            show_text_at(cairo, kLeft, kCaptionBaseline + static_cast<double>(i) * kRow,
                         elided_text(cairo, caption_[i], right - kLeft));
        }
    }
    // The legend: one entry for every kind of line in the plot, left to right.
    const double baseline = kCaptionBaseline + static_cast<double>(caption_.size()) * kRow + 4;
    double x = kLeft;
    const auto entry = [&](const std::string& label, const TraceStroke& stroke) {
        draw_legend_entry(cairo, x, baseline, label, stroke, (layers & legend) != 0,
                          (layers & legend_text) != 0);
        x += legend_entry_width(cairo, label) + kLegendGap;
    };
    for (const Trace& trace : kTraces) {
        entry(trace.label, trace.stroke);
    }
    entry("a bar begins", {bar_line_ink, 1.0, 4.0, 3.0});
    entry("the score ends (then the actuator rings out)", {end_line_ink, 1.0, 4.0, 3.0});
}

void ResponsePicture::draw_bar_labels(cairo_t* cairo, Layers layers) const {
    if (!(layers & bar_labels)) {
        return;
    }
    // Each bar's number at its start, and its clef where that changes; a label that would run
    // into the one before is left out (the bars are too short to name them all).
    const double baseline = plot_top() - kAbovePlot - 2;
    const double right = options_.width - kRight;
    select_font(cairo, 9, false);
    cairo_set_source_rgb(cairo, 0.2, 0.2, 0.2);
    double free_from = kLeft;
    std::string clef_before;
    std::size_t bar = static_cast<std::size_t>(-1);
    for (const auto& timing : performance_.timeline()) {
        if (timing.bar == bar) {
            continue;
        }
        bar = timing.bar;
        std::string label = std::to_string(bar + 1);
        if (bar < options_.bar_clefs.size() && options_.bar_clefs[bar] != clef_before) {
            clef_before = options_.bar_clefs[bar];
            label += " " + clef_before;
        }
        const double x = std::round(x_of(timing.onset)) + 3;
        const double width = text_width(cairo, label);
        if (x >= free_from && x + width <= right) {
            show_text_at(cairo, x, baseline, label);
            free_from = x + width + 6;
        }
    }
}

void ResponsePicture::draw_axes(cairo_t* cairo, Layers layers) const {
    PlotAxes axes;
    axes.left = kLeft;
    axes.top = plot_top();
    axes.right = options_.width - kRight;
    axes.bottom = options_.height - kBottom;
    axes.span_s = span_;
    axes.top_value = top_;
    axes.x_of = [this](double t) { return x_of(t); };
    axes.y_of = [this](double s) { return y_of(s); };
    axes.value_label = "strength (1 = the rated drive)";
    draw_plot_axes(cairo, axes, (layers & frame) != 0, (layers & axis_labels) != 0);
}

void ResponsePicture::draw_boundaries(cairo_t* cairo, Layers layers) const {
    if (!(layers & bar_boundaries)) {
        return;
    }
    const double bottom = options_.height - kBottom;
    cairo_set_dash(cairo, kBoundaryDashes, 2, 0);
    cairo_set_line_width(cairo, 1.0);
    const auto line_at = [&](double t) {
        const double x = std::round(x_of(t)) + 0.5;
        cairo_move_to(cairo, x, plot_top());
        cairo_line_to(cairo, x, bottom);
        cairo_stroke(cairo);
    };
    cairo_set_source_rgb(cairo, bar_line_ink[0], bar_line_ink[1], bar_line_ink[2]);
    std::size_t bar = static_cast<std::size_t>(-1);
    for (const auto& timing : performance_.timeline()) {
        if (timing.bar != bar && timing.onset > 0.0) {
            line_at(timing.onset);
        }
        bar = timing.bar;
    }
    // The score's end, after which the actuator only rings out.
    cairo_set_source_rgb(cairo, end_line_ink[0], end_line_ink[1], end_line_ink[2]);
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
        apply_stroke(cairo, trace.stroke);
        path(values);
        cairo_stroke(cairo);
    }
    cairo_set_dash(cairo, nullptr, 0, 0);
}

}  // namespace vibscore::pictures
