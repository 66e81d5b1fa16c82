#include "client/pictures/signal_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "client/pictures/axis_ticks.hpp"
#include "client/pictures/picture_text.hpp"
#include "daemon/render/sampler.hpp"

namespace vibscore::pictures {

namespace {

// The plot's frame inside the picture; above it, the title and legend, then the bar labels.
constexpr double kLeft = 58.0, kRight = 16.0, kTop = 48.0, kBottom = 42.0;
constexpr double kBarLabelBaseline = kTop - 4;
constexpr double kLegendWidth = 230.0;
constexpr int kSamplesPerPixel = 8;

}  // namespace

SignalPicture::SignalPicture(const render::Performance& performance, std::string title,
                             const Options& options)
    : performance_(performance), title_(std::move(title)), options_(options) {
    peak_ = performance.peak_amplitude() > 0.0 ? performance.peak_amplitude() : 1.0;
    // Sampled once, for every layer and file drawn from it.
    const double duration = performance_.duration();
    if (duration > 0.0) {
        const auto columns = static_cast<std::size_t>(options_.width - kLeft - kRight);
        rate_ = columns * kSamplesPerPixel / duration;
        const auto count = render::sample_index_at(duration, rate_);
        samples_.resize(count);
        strengths_.resize(count);
        render::render_signal(performance_, rate_, 0, samples_);
        render::render_envelope(performance_, rate_, 0, strengths_);
    }
}

double SignalPicture::x_of(double t) const {
    const double duration = performance_.duration() > 0.0 ? performance_.duration() : 1.0;
    return kLeft + t / duration * (options_.width - kLeft - kRight);
}

double SignalPicture::y_of(double y) const {
    const double middle = (kTop + options_.height - kBottom) / 2;
    const double half = (options_.height - kTop - kBottom) / 2 * 0.92;
    return middle - y / peak_ * half;
}

void SignalPicture::draw(cairo_t* cairo, Layers layers) const {
    draw_title_and_legend(cairo, layers);
    draw_boundaries(cairo, layers);
    draw_signal(cairo, layers);
    draw_axes(cairo, layers);
}

void SignalPicture::draw_title_and_legend(cairo_t* cairo, Layers layers) const {
    const double right = options_.width - kRight;
    if (layers & title) {
        cairo_set_source_rgb(cairo, 0, 0, 0);
        select_font(cairo, 14, true);
        // A long title is cut short before the legend.
        show_text_at(cairo, kLeft, 20,
                     elided_text(cairo, title_, right - kLegendWidth - 12 - kLeft));
    }
    struct Entry {
        double x;
        double rgb[3];
        const char* text;
    };
    for (const Entry& entry : {Entry{right - kLegendWidth, {0.25, 0.4, 0.75}, "signal y(t)"},
                               Entry{right - 120, {0.85, 0.2, 0.1}, "envelope"}}) {
        if (layers & legend) {
            cairo_set_line_width(cairo, 2.0);
            cairo_set_source_rgb(cairo, entry.rgb[0], entry.rgb[1], entry.rgb[2]);
            cairo_move_to(cairo, entry.x, 16);
            cairo_line_to(cairo, entry.x + 20, 16);
            cairo_stroke(cairo);
        }
        if (layers & legend_text) {
            select_font(cairo, 10, false);
            cairo_set_source_rgb(cairo, 0, 0, 0);
            show_text_at(cairo, entry.x + 25, 20, entry.text);
        }
    }
}

void SignalPicture::draw_axes(cairo_t* cairo, Layers layers) const {
    const double bottom = options_.height - kBottom;
    const double right = options_.width - kRight;
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_line_width(cairo, 1.0);
    if (layers & frame) {
        cairo_rectangle(cairo, kLeft + 0.5, kTop + 0.5, right - kLeft, bottom - kTop);
        cairo_stroke(cairo);
    }
    select_font(cairo, 10, false);
    const double duration = performance_.duration();
    const double step = tick_step(std::max(duration, 1e-3), 10);
    for (double t = 0.0; t <= duration + step * 1e-6; t += step) {
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
    if (!(layers & axis_labels)) {
        return;
    }
    show_text_at(cairo, right - 40, bottom + 33, "t (s)");
    char peak[32];
    std::snprintf(peak, sizeof peak, "%.3g", peak_);
    for (const double level : {1.0, 0.0, -1.0}) {
        const std::string label =
            level == 0.0 ? "0" : (level > 0 ? std::string(peak) : "-" + std::string(peak));
        // Right-aligned against the frame, however long the number.
        show_text_at(cairo, kLeft - 6 - text_width(cairo, label), y_of(level * peak_) + 4, label);
    }
}

void SignalPicture::draw_boundaries(cairo_t* cairo, Layers layers) const {
    const double bottom = options_.height - kBottom;
    // Where each bar begins, to give each label the room before the next.
    std::vector<std::pair<std::size_t, double>> bar_starts;
    for (const auto& timing : performance_.timeline()) {
        const double x = std::round(x_of(timing.onset)) + 0.5;
        if (bar_starts.empty() || timing.bar != bar_starts.back().first) {
            bar_starts.emplace_back(timing.bar, x);
            if (layers & bar_boundaries) {
                const double dashes[] = {4.0, 3.0};
                cairo_set_dash(cairo, dashes, 2, 0);
                cairo_set_source_rgb(cairo, 0.3, 0.3, 0.3);
                cairo_set_line_width(cairo, 1.0);
                cairo_move_to(cairo, x, kTop);
                cairo_line_to(cairo, x, bottom);
                cairo_stroke(cairo);
                cairo_set_dash(cairo, nullptr, 0, 0);
            }
        } else if (layers & note_boundaries) {
            cairo_set_source_rgb(cairo, 0.78, 0.78, 0.78);
            cairo_set_line_width(cairo, 1.0);
            cairo_move_to(cairo, x, kTop);
            cairo_line_to(cairo, x, bottom);
            cairo_stroke(cairo);
        }
    }
    if (!(layers & bar_labels)) {
        return;
    }
    // Above the frame, each label within its bar: "bar 12", or "12" where bars are narrow, or
    // none where not even that fits.
    select_font(cairo, 9, false);
    cairo_set_source_rgb(cairo, 0.3, 0.3, 0.3);
    for (std::size_t i = 0; i < bar_starts.size(); ++i) {
        const auto [bar, x] = bar_starts[i];
        const double end =
            i + 1 < bar_starts.size() ? bar_starts[i + 1].second : x_of(performance_.duration());
        const auto number = std::to_string(bar + 1);
        const auto label = fitted_text(cairo, {"bar " + number, number}, end - x - 6);
        show_text_at(cairo, x + 3, kBarLabelBaseline, label);
    }
}

void SignalPicture::draw_signal(cairo_t* cairo, Layers layers) const {
    const auto curve = [&](const std::vector<double>& values, double sign) {
        for (std::size_t k = 0; k < values.size(); ++k) {
            const double x = x_of(static_cast<double>(k) / rate_);
            const double y = y_of(sign * values[k]);
            k == 0 ? cairo_move_to(cairo, x, y) : cairo_line_to(cairo, x, y);
        }
        cairo_stroke(cairo);
    };
    cairo_set_line_join(cairo, CAIRO_LINE_JOIN_BEVEL);  // half the time of round joins
    if ((layers & signal) && !samples_.empty()) {
        cairo_set_source_rgb(cairo, 0.25, 0.4, 0.75);
        cairo_set_line_width(cairo, 0.8);
        curve(samples_, 1.0);
    }
    if ((layers & envelope) && !strengths_.empty()) {
        cairo_set_source_rgb(cairo, 0.85, 0.2, 0.1);
        cairo_set_line_width(cairo, 1.4);
        curve(strengths_, 1.0);
        curve(strengths_, -1.0);
    }
}

}  // namespace vibscore::pictures
