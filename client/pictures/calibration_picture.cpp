#include "client/pictures/calibration_picture.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "client/pictures/picture_text.hpp"
#include "client/pictures/plot_axes.hpp"
#include "client/pictures/trace_stroke.hpp"

namespace vibscore::pictures {

namespace {

constexpr double kLeft = 58.0, kRight = 16.0, kTop = 50.0, kBottom = 42.0;
constexpr double kTitleBaseline = 20.0, kCaptionBaseline = 38.0;
constexpr double kLegendGap = 16.0;

struct Entry {
    CalibrationPicture::Layer layer;
    TraceStroke stroke;
    const char* label;
};

// The recording thin (it is noisy), the fit solid and widest, the declaration dashed: the two
// models stay apart where they agree.
constexpr Entry kEntries[] = {
    {CalibrationPicture::recorded, {CalibrationPicture::recorded_ink, 1.0}, "recorded"},
    {CalibrationPicture::fitted, {CalibrationPicture::fitted_ink, 1.8}, "model, measured numbers"},
    {CalibrationPicture::declared,
     {CalibrationPicture::declared_ink, 1.6, 6.0, 3.0},
     "model, declared numbers"},
};

double largest(const actuator::calibration::Trace& trace) {
    double peak = 0.0;
    for (const double value : trace.magnitude) {
        if (std::isfinite(value)) {
            peak = std::max(peak, std::abs(value));
        }
    }
    return peak;
}

double last_time(const actuator::calibration::Trace& trace) {
    return trace.t_s.empty() ? 0.0 : trace.t_s.back();
}

}  // namespace

CalibrationPicture::CalibrationPicture(Traces traces, std::string title, std::string caption,
                                       const Options& options)
    : traces_(std::move(traces)),
      title_(std::move(title)),
      caption_(std::move(caption)),
      options_(options) {
    const double peak =
        std::max({largest(traces_.recorded), largest(traces_.fitted), largest(traces_.declared)});
    top_ = peak > 0.0 ? peak * 1.08 : 1.0;
    span_ = std::max({last_time(traces_.recorded), last_time(traces_.fitted),
                      last_time(traces_.declared), 1e-3});
}

double CalibrationPicture::x_of(double t) const {
    return kLeft + t / span_ * (options_.width - kLeft - kRight);
}

double CalibrationPicture::y_of(double accel) const {
    const double bottom = options_.height - kBottom;
    return bottom - accel / top_ * (bottom - kTop);
}

void CalibrationPicture::draw(cairo_t* cairo, Layers layers) const {
    draw_header(cairo, layers);
    draw_traces(cairo, layers);
    draw_axes(cairo, layers);
}

void CalibrationPicture::draw_header(cairo_t* cairo, Layers layers) const {
    const double right = options_.width - kRight;
    std::vector<double> entry_x(std::size(kEntries));
    double x = right;
    for (std::size_t i = std::size(kEntries); i-- > 0;) {
        x -= legend_entry_width(cairo, kEntries[i].label);
        entry_x[i] = x;
        x -= kLegendGap;
    }
    const double legend_left = x;
    for (std::size_t i = 0; i < std::size(kEntries); ++i) {
        draw_legend_entry(cairo, entry_x[i], kTitleBaseline, kEntries[i].label, kEntries[i].stroke,
                          (layers & legend) != 0, (layers & legend_text) != 0);
    }
    if (layers & title) {
        cairo_set_source_rgb(cairo, 0, 0, 0);
        select_font(cairo, 14, true);
        show_text_at(cairo, kLeft, kTitleBaseline,
                     elided_text(cairo, title_, legend_left - 12 - kLeft));
    }
    if (layers & caption) {
        cairo_set_source_rgb(cairo, 0.3, 0.3, 0.3);
        select_font(cairo, 10, false);
        show_text_at(cairo, kLeft, kCaptionBaseline, elided_text(cairo, caption_, right - kLeft));
    }
}

void CalibrationPicture::draw_axes(cairo_t* cairo, Layers layers) const {
    PlotAxes axes;
    axes.left = kLeft;
    axes.top = kTop;
    axes.right = options_.width - kRight;
    axes.bottom = options_.height - kBottom;
    axes.span_s = span_;
    axes.top_value = top_;
    axes.x_of = [this](double t) { return x_of(t); };
    axes.y_of = [this](double a) { return y_of(a); };
    axes.value_label = "vibration (m/s\u00b2, gravity taken out)";
    draw_plot_axes(cairo, axes, (layers & frame) != 0, (layers & axis_labels) != 0);
}

void CalibrationPicture::draw_traces(cairo_t* cairo, Layers layers) const {
    cairo_set_line_join(cairo, CAIRO_LINE_JOIN_BEVEL);
    for (const Entry& entry : kEntries) {
        const auto& trace = entry.layer == recorded ? traces_.recorded
                            : entry.layer == fitted ? traces_.fitted
                                                    : traces_.declared;
        if (!(layers & entry.layer) || trace.t_s.empty()) {
            continue;
        }
        const std::size_t count = std::min(trace.t_s.size(), trace.magnitude.size());
        bool drawing = false;
        for (std::size_t k = 0; k < count; ++k) {
            if (!std::isfinite(trace.magnitude[k])) {
                drawing = false;  // a gap the estimate could not fill is left open
                continue;
            }
            const double x = x_of(trace.t_s[k]);
            const double y = y_of(trace.magnitude[k]);
            drawing ? cairo_line_to(cairo, x, y) : cairo_move_to(cairo, x, y);
            drawing = true;
        }
        apply_stroke(cairo, entry.stroke);
        cairo_stroke(cairo);
    }
    cairo_set_dash(cairo, nullptr, 0, 0);
}

}  // namespace vibscore::pictures
