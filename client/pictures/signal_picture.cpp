#include "client/pictures/signal_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "daemon/render/sampler.hpp"

namespace vibscore::pictures {

namespace {

constexpr double kLeft = 58.0, kRight = 16.0, kTop = 34.0, kBottom = 42.0;
constexpr int kSamplesPerPixel = 8;

std::string seconds_label(double t, double step) {
    char text[32];
    std::snprintf(text, sizeof text, step < 0.1 ? "%.2f" : step < 1 ? "%.1f" : "%.0f", t);
    return text;
}

// A round step for about `count` ticks over `span`: 1, 2 or 5 times a power of ten.
double tick_step(double span, int count) {
    const double rough = span / count;
    const double power = std::pow(10.0, std::floor(std::log10(rough)));
    for (const double factor : {1.0, 2.0, 5.0, 10.0}) {
        if (factor * power >= rough) {
            return factor * power;
        }
    }
    return 10 * power;
}

void font(cairo_t* cairo, double size, bool bold) {
    cairo_select_font_face(cairo, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cairo, size);
}

}  // namespace

SignalPicture::SignalPicture(const render::Performance& performance, std::string title,
                             const Options& options)
    : performance_(performance), title_(std::move(title)), options_(options) {
    peak_ = performance.peak_amplitude() > 0.0 ? performance.peak_amplitude() : 1.0;
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

void SignalPicture::draw(cairo_t* cairo) const {
    cairo_set_source_rgb(cairo, 0, 0, 0);
    font(cairo, 14, true);
    cairo_move_to(cairo, kLeft, 20);
    cairo_show_text(cairo, title_.c_str());
    draw_boundaries(cairo);
    draw_signal(cairo);
    draw_axes(cairo);
}

void SignalPicture::draw_axes(cairo_t* cairo) const {
    const double bottom = options_.height - kBottom;
    const double right = options_.width - kRight;
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_line_width(cairo, 1.0);
    cairo_rectangle(cairo, kLeft + 0.5, kTop + 0.5, right - kLeft, bottom - kTop);
    cairo_stroke(cairo);
    font(cairo, 10, false);
    const double duration = performance_.duration();
    const double step = tick_step(std::max(duration, 1e-3), 10);
    for (double t = 0.0; t <= duration + step * 1e-6; t += step) {
        const double x = std::round(x_of(t)) + 0.5;
        cairo_move_to(cairo, x, bottom);
        cairo_line_to(cairo, x, bottom + 5);
        cairo_stroke(cairo);
        const auto label = seconds_label(t, step);
        cairo_text_extents_t extents;
        cairo_text_extents(cairo, label.c_str(), &extents);
        cairo_move_to(cairo, x - extents.width / 2, bottom + 17);
        cairo_show_text(cairo, label.c_str());
    }
    cairo_move_to(cairo, right - 40, bottom + 33);
    cairo_show_text(cairo, "t (s)");
    char peak[32];
    std::snprintf(peak, sizeof peak, "%.3g", peak_);
    for (const double level : {1.0, 0.0, -1.0}) {
        const std::string label =
            level == 0.0 ? "0" : (level > 0 ? std::string(peak) : "-" + std::string(peak));
        cairo_move_to(cairo, 6, y_of(level * peak_) + 4);
        cairo_show_text(cairo, label.c_str());
    }
    // Legend.
    cairo_set_line_width(cairo, 2.0);
    cairo_set_source_rgb(cairo, 0.25, 0.4, 0.75);
    cairo_move_to(cairo, right - 230, 16);
    cairo_line_to(cairo, right - 210, 16);
    cairo_stroke(cairo);
    cairo_set_source_rgb(cairo, 0.85, 0.2, 0.1);
    cairo_move_to(cairo, right - 120, 16);
    cairo_line_to(cairo, right - 100, 16);
    cairo_stroke(cairo);
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_move_to(cairo, right - 205, 20);
    cairo_show_text(cairo, "signal y(t)");
    cairo_move_to(cairo, right - 95, 20);
    cairo_show_text(cairo, "envelope");
}

void SignalPicture::draw_boundaries(cairo_t* cairo) const {
    const double bottom = options_.height - kBottom;
    std::size_t bar = static_cast<std::size_t>(-1);
    font(cairo, 9, false);
    for (const auto& timing : performance_.timeline()) {
        const double x = std::round(x_of(timing.onset)) + 0.5;
        if (timing.bar != bar) {
            bar = timing.bar;
            const double dashes[] = {4.0, 3.0};
            cairo_set_dash(cairo, dashes, 2, 0);
            cairo_set_source_rgb(cairo, 0.3, 0.3, 0.3);
            cairo_set_line_width(cairo, 1.0);
            cairo_move_to(cairo, x, kTop);
            cairo_line_to(cairo, x, bottom);
            cairo_stroke(cairo);
            cairo_set_dash(cairo, nullptr, 0, 0);
            cairo_move_to(cairo, x + 3, kTop + 11);
            cairo_show_text(cairo, ("bar " + std::to_string(bar + 1)).c_str());
        } else {
            cairo_set_source_rgb(cairo, 0.78, 0.78, 0.78);
            cairo_set_line_width(cairo, 1.0);
            cairo_move_to(cairo, x, kTop + 14);
            cairo_line_to(cairo, x, bottom);
            cairo_stroke(cairo);
        }
    }
}

void SignalPicture::draw_signal(cairo_t* cairo) const {
    const double duration = performance_.duration();
    if (duration <= 0.0) {
        return;
    }
    const auto columns = static_cast<std::size_t>(options_.width - kLeft - kRight);
    const double rate = columns * kSamplesPerPixel / duration;
    const auto count = render::sample_index_at(duration, rate);
    std::vector<double> signal(count), envelope(count);
    render::render_signal(performance_, rate, 0, signal);
    render::render_envelope(performance_, rate, 0, envelope);

    cairo_set_line_join(cairo, CAIRO_LINE_JOIN_ROUND);
    cairo_set_source_rgb(cairo, 0.25, 0.4, 0.75);
    cairo_set_line_width(cairo, 0.8);
    for (std::size_t k = 0; k < count; ++k) {
        const double x = x_of(static_cast<double>(k) / rate);
        k == 0 ? cairo_move_to(cairo, x, y_of(signal[k]))
               : cairo_line_to(cairo, x, y_of(signal[k]));
    }
    cairo_stroke(cairo);
    cairo_set_source_rgb(cairo, 0.85, 0.2, 0.1);
    cairo_set_line_width(cairo, 1.4);
    for (const double sign : {1.0, -1.0}) {
        for (std::size_t k = 0; k < count; ++k) {
            const double x = x_of(static_cast<double>(k) / rate);
            const double y = y_of(sign * envelope[k]);
            k == 0 ? cairo_move_to(cairo, x, y) : cairo_line_to(cairo, x, y);
        }
        cairo_stroke(cairo);
    }
}

}  // namespace vibscore::pictures
