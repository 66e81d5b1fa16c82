#include "client/pictures/clef_picture.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "actuator/physics.hpp"
#include "client/pictures/axis_ticks.hpp"
#include "client/pictures/picture_text.hpp"
#include "common/number_text.hpp"
#include "daemon/render/waveform.hpp"

namespace vibscore::pictures {

namespace {

constexpr double kMargin = 14.0;
constexpr double kLeft = 72.0;  // room for the string names and level labels of shape plots
constexpr double kTop = 64.0;   // below the title, and the string numbers over a sine plot
constexpr double kPlotWidth = 520.0;
constexpr double kSineHeight = 250.0;
constexpr double kShapeHeight = 52.0, kShapeGap = 18.0;
constexpr double kBelowPlots = 44.0;   // tick labels and the axis title
constexpr double kTableGap = 48.0;     // between a plot (and its number labels) and the table
constexpr double kRow = 15.0;          // a table row
constexpr int kShapeSamples = 1024;    // over a quarter note
constexpr int kResponseSamples = 520;  // one per pixel of the plot's width
constexpr double kReachedHalfWidth = 6.0;

constexpr double kResponseInk[3] = {0.95, 0.55, 0.15};

constexpr double kStringInk[3] = {0.25, 0.4, 0.75};
constexpr double kPointInk[3] = {0.85, 0.2, 0.1};
constexpr double kNoteInk[3] = {0.08, 0.08, 0.25};  // as the staff's note heads

void set_rgb(cairo_t* cairo, const double (&rgb)[3]) {
    cairo_set_source_rgb(cairo, rgb[0], rgb[1], rgb[2]);
}

// The lowest and highest level a shape clef's waveforms reach: a curve may overshoot its points.
std::pair<double, double> level_range(const Clef& clef) {
    double low = 0.0, high = 1.0;
    for (const auto& string : clef.strings) {
        const render::Waveform waveform(clef.type, string.points);
        std::size_t hint = 0;
        for (int k = 0; k <= kShapeSamples; ++k) {
            const double level = waveform.level(static_cast<double>(k) / kShapeSamples, hint);
            low = std::min(low, level);
            high = std::max(high, level);
        }
    }
    return {low, high};
}

// The waveform as a polyline over tau 0..1: straight between a line's points, sampled finely
// between a curve's, and vertical at a step (two points at one time) and at a line's corners,
// exactly where the points are.
std::vector<ClefPoint> outline(const Clef& clef, const std::vector<ClefPoint>& points) {
    const render::Waveform waveform(clef.type, points);
    std::vector<ClefPoint> result{{0.0, points.front().level}};
    for (std::size_t i = 0; i < points.size(); ++i) {
        const ClefPoint& point = points[i];
        if (clef.type == ClefType::curve && i > 0 && points[i - 1].time < point.time) {
            const double from = points[i - 1].time;
            const int samples = static_cast<int>(std::ceil((point.time - from) * kShapeSamples));
            for (int k = 1; k < samples; ++k) {
                const double tau = from + (point.time - from) * k / samples;
                result.push_back({tau, waveform.level(tau)});
            }
        }
        result.push_back(point);
    }
    result.push_back({1.0, points.back().level});
    return result;
}

}  // namespace

ClefPicture::ClefPicture(const Clef& clef, std::string name,
                         std::optional<actuator::Declaration> actuator)
    : clef_(clef), actuator_(std::move(actuator)) {
    title_ = name + ": " + std::string(to_string(clef.type)) + " clef, a quarter note lasts " +
             number_text(clef.tempo) + " s";
    if (actuator_) {
        caption_.push_back("on the actuator: " + actuator::describe(*actuator_));
        if (actuator_->kind == actuator::Kind::erm) {
            caption_.push_back(clef.type == ClefType::sine
                                   ? "an ERM has no pitch: it plays every string alike, at the "
                                     "strengths marked"
                                   : "an ERM has no pitch: only the shapes are felt");
        } else if (clef.type == ClefType::sine) {
            caption_.push_back(
                "curve: the strength full drive gives; rings: each number's strength as "
                "written; marks: the strength it reaches on each string");
        } else {
            caption_.push_back("the LRA plays these shapes at its resonance");
        }
    }
    double bottom = kTop;
    if (clef.type == ClefType::sine) {
        Plot plot{kLeft, kTop, kPlotWidth, kSineHeight};
        double low = clef.strings.front().frequency, high = low;
        for (const auto& string : clef.strings) {
            low = std::min(low, string.frequency);
            high = std::max(high, string.frequency);
        }
        // The strings' span with room on both sides; a single frequency gets ±20 %.
        const double pad = high > low ? (high - low) * 0.12 : std::max(low * 0.2, 1.0);
        plot.x_from = std::max(0.0, low - pad);
        plot.x_to = high + pad;
        double loudest = *std::max_element(clef.numbers.begin(), clef.numbers.end());
        if (actuator_ && actuator_->kind == actuator::Kind::lra) {
            // The response's peak too, where it is inside the plot.
            for (int k = 0; k <= kResponseSamples; ++k) {
                loudest =
                    std::max(loudest, full_drive_strength(plot.x_from + (plot.x_to - plot.x_from) *
                                                                            k / kResponseSamples));
            }
        }
        plot.y_to = loudest > 0.0 ? loudest * 1.12 : 1.0;
        // A number at (or near) 0 sits above the frame, not on it.
        plot.y_from = -0.06 * plot.y_to;
        plots_.push_back(plot);
        bottom = kTop + kSineHeight;
    } else {
        const auto [low, high] = level_range(clef);
        const auto count = static_cast<double>(clef.strings.size());
        for (std::size_t s = 0; s < clef.strings.size(); ++s) {
            // String 6 on top, as on the staff.
            const double top =
                kTop + (count - 1 - static_cast<double>(s)) * (kShapeHeight + kShapeGap);
            const double room = (high - low) * 0.08;
            plots_.push_back(
                {kLeft, top, kPlotWidth, kShapeHeight, 0.0, clef.tempo, low - room, high + room});
        }
        bottom = kTop + count * (kShapeHeight + kShapeGap) - kShapeGap;
    }
    if (!caption_.empty()) {
        caption_top_ = bottom + kBelowPlots + 6;
        bottom += static_cast<double>(caption_.size()) * kRow + 6;
    }
    table_left_ = kLeft + kPlotWidth + kTableGap;
    const double rows = clef.type == ClefType::sine
                            ? 3.0 + clef.strings.size() + clef.numbers.size()
                            : 1.0 + clef.numbers.size();
    height_ = std::ceil(std::max(bottom + kBelowPlots, kTop + rows * kRow + kMargin));
    // Wide enough for the title and the table's widest row.
    const SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1),
                             &cairo_surface_destroy);
    const CairoPtr measure(cairo_create(scratch.get()), &cairo_destroy);
    select_font(measure.get(), 14, true);
    double text_right = kMargin + text_width(measure.get(), title_);
    select_font(measure.get(), 10, false);
    for (const auto& line : caption_) {
        text_right = std::max(text_right, kMargin + text_width(measure.get(), line));
    }
    width_ = std::ceil(std::max(table_left_ + 190, text_right + kMargin));
}

double ClefPicture::full_drive_strength(double frequency_hz) const {
    if (!actuator_) {
        return 0.0;
    }
    return actuator::Physics(*actuator_).steady_strength({1.0, frequency_hz});
}

double ClefPicture::reached_strength(std::size_t s, std::size_t n) const {
    if (!actuator_) {
        return 0.0;
    }
    const actuator::Physics physics(*actuator_);
    const double frequency = clef_.type == ClefType::sine ? clef_.strings.at(s).frequency : 0.0;
    const double number = clef_.numbers.at(n);
    // The drive the renderer holds a note with (render::DrivePlanner; uncompensated, the
    // written strength times rated-drive), never more than full scale.
    const double drive = actuator_->compensation ? physics.amplitude_for(number, frequency)
                                                 : number * actuator_->rated_drive;
    return physics.steady_strength({std::min(1.0, drive), frequency});
}

void ClefPicture::draw(cairo_t* cairo, Layers layers) const {
    if (layers & title) {
        cairo_set_source_rgb(cairo, 0, 0, 0);
        select_font(cairo, 14, true);
        show_text_at(cairo, kMargin, 22, title_);
    }
    if (clef_.type == ClefType::sine) {
        draw_response(cairo, layers);
        draw_sine(cairo, layers);
        // Last, over the number's dots: what each number reaches is the point of the picture.
        draw_reached(cairo, layers);
    } else {
        draw_shapes(cairo, layers);
    }
    draw_table(cairo, layers);
    draw_caption(cairo, layers);
}

void ClefPicture::draw_response(cairo_t* cairo, Layers layers) const {
    if (!actuator_) {
        return;
    }
    const Plot& plot = plots_.front();
    cairo_save(cairo);
    // Inside the frame only: a response higher than the plot is cut at its top.
    cairo_rectangle(cairo, std::round(plot.left) + 1, std::round(plot.top) + 1,
                    std::round(plot.width) - 1, std::round(plot.height) - 1);
    cairo_clip(cairo);
    if ((layers & response) && actuator_->kind == actuator::Kind::lra) {
        set_rgb(cairo, kResponseInk);
        cairo_set_line_width(cairo, 2.0);
        cairo_set_line_join(cairo, CAIRO_LINE_JOIN_ROUND);
        for (int k = 0; k <= kResponseSamples; ++k) {
            const double f = plot.x_from + (plot.x_to - plot.x_from) * k / kResponseSamples;
            const double x = plot.x_of(f), y = plot.y_of(full_drive_strength(f));
            k == 0 ? cairo_move_to(cairo, x, y) : cairo_line_to(cairo, x, y);
        }
        cairo_stroke(cairo);
    }
    cairo_restore(cairo);
}

void ClefPicture::draw_reached(cairo_t* cairo, Layers layers) const {
    if (!actuator_ || !(layers & reached)) {
        return;
    }
    const Plot& plot = plots_.front();
    cairo_save(cairo);
    cairo_rectangle(cairo, std::round(plot.left) + 1, std::round(plot.top) + 1,
                    std::round(plot.width) - 1, std::round(plot.height) - 1);
    cairo_clip(cairo);
    {
        set_rgb(cairo, ClefPicture::reached_ink);
        cairo_set_line_width(cairo, 2.0);
        for (std::size_t s = 0; s < clef_.strings.size(); ++s) {
            const double x = std::round(plot.x_of(clef_.strings[s].frequency)) + 0.5;
            for (std::size_t n = 0; n < clef_.numbers.size(); ++n) {
                const double y = std::round(plot.y_of(reached_strength(s, n))) + 0.5;
                cairo_move_to(cairo, x - kReachedHalfWidth, y);
                cairo_line_to(cairo, x + kReachedHalfWidth, y);
                cairo_stroke(cairo);
            }
        }
    }
    cairo_restore(cairo);
}

void ClefPicture::draw_caption(cairo_t* cairo, Layers layers) const {
    if (!(layers & caption) || caption_.empty()) {
        return;
    }
    cairo_set_source_rgb(cairo, 0, 0, 0);
    select_font(cairo, 10, false);
    double y = caption_top_;
    for (const auto& line : caption_) {
        show_text_at(cairo, kMargin, y, line);
        y += kRow;
    }
}

void ClefPicture::draw_frame(cairo_t* cairo, const Plot& plot, Layers layers, bool x_labels,
                             const char* x_title) const {
    const double bottom = plot.top + plot.height;
    const double x_step = tick_step(plot.x_to - plot.x_from, 8);
    select_font(cairo, 10, false);
    cairo_set_line_width(cairo, 1.0);
    cairo_set_source_rgb(cairo, 0, 0, 0);
    if (layers & frames) {
        cairo_rectangle(cairo, std::round(plot.left) + 0.5, std::round(plot.top) + 0.5,
                        std::round(plot.width), std::round(plot.height));
        cairo_stroke(cairo);
    }
    for (double x = std::ceil(plot.x_from / x_step) * x_step; x <= plot.x_to + x_step * 1e-9;
         x += x_step) {
        const double at = std::round(plot.x_of(x)) + 0.5;
        if (layers & frames) {
            cairo_move_to(cairo, at, std::round(bottom) + 1);
            cairo_line_to(cairo, at, std::round(bottom) + 5);
            cairo_stroke(cairo);
        }
        if (x_labels && (layers & axis_labels)) {
            const auto label = tick_label(x, x_step);
            show_text_at(cairo, at - text_width(cairo, label) / 2, bottom + 17, label);
        }
    }
    if (x_labels && (layers & axis_labels)) {
        show_text_at(cairo, plot.left + plot.width - text_width(cairo, x_title), bottom + 34,
                     x_title);
    }
}

void ClefPicture::draw_sine(cairo_t* cairo, Layers layers) const {
    const Plot& plot = plots_.front();
    const double right = plot.left + plot.width;
    draw_frame(cairo, plot, layers, true, "frequency (Hz)");
    // The strength axis: ticks on the left, the numbers' own lines across.
    const double y_step = tick_step(plot.y_to - plot.y_from, 5);
    select_font(cairo, 10, false);
    for (double y = 0.0; y <= plot.y_to + y_step * 1e-9; y += y_step) {
        const double at = std::round(plot.y_of(y)) + 0.5;
        if (layers & frames) {
            cairo_set_source_rgb(cairo, 0, 0, 0);
            cairo_move_to(cairo, plot.left - 4, at);
            cairo_line_to(cairo, plot.left, at);
            cairo_stroke(cairo);
        }
        if (layers & axis_labels) {
            const auto label = tick_label(y, y_step);
            show_text_at(cairo, plot.left - 7 - text_width(cairo, label), at + 4, label);
        }
    }
    if (layers & axis_labels) {
        show_text_at(cairo, kMargin, kTop - 10, "strength");
    }
    if (layers & numbers) {
        const double dashes[] = {3.0, 3.0};
        cairo_set_dash(cairo, dashes, 2, 0);
        cairo_set_source_rgb(cairo, 0.55, 0.55, 0.55);
        for (const double strength : clef_.numbers) {
            const double y = std::round(plot.y_of(strength)) + 0.5;
            cairo_move_to(cairo, plot.left + 1, y);
            cairo_line_to(cairo, right, y);
            cairo_stroke(cairo);
        }
        cairo_set_dash(cairo, nullptr, 0, 0);
    }
    if (layers & strings) {
        set_rgb(cairo, kStringInk);
        cairo_set_line_width(cairo, 1.5);
        for (const auto& string : clef_.strings) {
            const double x = std::round(plot.x_of(string.frequency)) + 0.5;
            cairo_move_to(cairo, x, plot.top + 1);
            cairo_line_to(cairo, x, plot.top + plot.height);
            cairo_stroke(cairo);
        }
    }
    if (layers & notes) {
        set_rgb(cairo, kNoteInk);
        // Over an actuator's response the written dots are rings, so the mark of what a number
        // reaches shows through where the two meet.
        const bool rings = actuator_.has_value();
        cairo_set_line_width(cairo, 1.2);
        for (const auto& string : clef_.strings) {
            for (const double strength : clef_.numbers) {
                cairo_new_sub_path(cairo);
                cairo_arc(cairo, std::round(plot.x_of(string.frequency)) + 0.5,
                          std::round(plot.y_of(strength)) + 0.5, 3.2, 0, 2 * M_PI);
                rings ? cairo_stroke(cairo) : cairo_fill(cairo);
            }
        }
    }
    if (!(layers & axis_labels)) {
        return;
    }
    // Which string and which number each line is; where two would touch, the table says it.
    cairo_set_source_rgb(cairo, 0, 0, 0);
    select_font(cairo, 10, true);
    double free_from = plot.left;
    for (std::size_t s = 0; s < clef_.strings.size(); ++s) {
        const auto label = std::to_string(s + 1);
        const double x = plot.x_of(clef_.strings[s].frequency) - text_width(cairo, label) / 2;
        if (x >= free_from) {
            show_text_at(cairo, x, plot.top - 6, label);
            free_from = x + text_width(cairo, label) + 4;
        }
    }
    double free_below = plot.top + plot.height + 12;
    for (std::size_t n = 0; n < clef_.numbers.size(); ++n) {
        const double y = plot.y_of(clef_.numbers[n]) + 4;
        if (y <= free_below) {
            show_text_at(cairo, right + 6, y, std::to_string(n + 1));
            free_below = y - 12;
        }
    }
}

void ClefPicture::draw_shapes(cairo_t* cairo, Layers layers) const {
    for (std::size_t s = 0; s < clef_.strings.size(); ++s) {
        const Plot& plot = plots_[s];
        draw_frame(cairo, plot, layers, s == 0, "time in a quarter note (s)");
        select_font(cairo, 10, false);
        cairo_set_source_rgb(cairo, 0, 0, 0);
        for (const double level : {0.0, 1.0}) {
            const double at = std::round(plot.y_of(level)) + 0.5;
            if (layers & frames) {
                cairo_move_to(cairo, plot.left - 4, at);
                cairo_line_to(cairo, plot.left, at);
                cairo_stroke(cairo);
            }
            if (layers & axis_labels) {
                const auto label = tick_label(level, 1.0);
                show_text_at(cairo, plot.left - 7 - text_width(cairo, label), at + 4, label);
            }
        }
        if (layers & axis_labels) {
            select_font(cairo, 10, true);
            show_text_at(cairo, kMargin, plot.top + plot.height / 2 + 4,
                         "string " + std::to_string(s + 1));
        }
        const auto& controls = clef_.strings[s].points;
        if (layers & strings) {
            set_rgb(cairo, kStringInk);
            cairo_set_line_width(cairo, 1.4);
            cairo_set_line_join(cairo, CAIRO_LINE_JOIN_BEVEL);
            bool first = true;
            for (const auto& point : outline(clef_, controls)) {
                const double x = plot.x_of(point.time * clef_.tempo), y = plot.y_of(point.level);
                first ? cairo_move_to(cairo, x, y) : cairo_line_to(cairo, x, y);
                first = false;
            }
            cairo_stroke(cairo);
        }
        if (layers & points) {
            // Dense points shrink, so that each stays a dot of its own.
            const double spacing = plot.width / std::max<std::size_t>(controls.size(), 1);
            const double radius = std::clamp(spacing / 2.5, 1.0, 2.6);
            set_rgb(cairo, kPointInk);
            for (const auto& point : controls) {
                cairo_arc(cairo, plot.x_of(point.time * clef_.tempo), plot.y_of(point.level),
                          radius, 0, 2 * M_PI);
                cairo_fill(cairo);
            }
        }
    }
}

void ClefPicture::draw_table(cairo_t* cairo, Layers layers) const {
    if (!(layers & table)) {
        return;
    }
    cairo_set_source_rgb(cairo, 0, 0, 0);
    double y = kTop - 10;
    const auto heading = [&](const std::string& text) {
        select_font(cairo, 10, true);
        show_text_at(cairo, table_left_, y, text);
        y += kRow;
    };
    const auto row = [&](const std::string& key, const std::string& value) {
        select_font(cairo, 10, false);
        show_text_at(cairo, table_left_ + 18 - text_width(cairo, key), y, key);
        show_text_at(cairo, table_left_ + 30, y, value);
        y += kRow;
    };
    if (clef_.type == ClefType::sine) {
        heading("string   frequency");
        for (std::size_t s = clef_.strings.size(); s-- > 0;) {
            row(std::to_string(s + 1), number_text(clef_.strings[s].frequency) + " Hz");
        }
        y += kRow;
        heading("number   strength");
    } else {
        heading("number   scales the level by");
    }
    for (std::size_t n = 0; n < clef_.numbers.size(); ++n) {
        row(std::to_string(n + 1), number_text(clef_.numbers[n]));
    }
}

}  // namespace vibscore::pictures
