#include "client/terminal_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "daemon/render/sampler.hpp"

namespace vibscore::client {

namespace {

// Eighth blocks, from empty to full, give each row eight levels.
constexpr std::array<const char*, 9> kBlocks{" ", "▁", "▂", "▃", "▄", "▅", "▆", "▇", "█"};
constexpr int kSamplesPerColumn = 32;

std::string seconds(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g s", value);
    return text;
}

// The largest of `samples` within each of `width` columns.
std::vector<double> column_peaks(const std::vector<double>& samples, int width) {
    std::vector<double> column(static_cast<std::size_t>(width), 0.0);
    for (std::size_t i = 0; i < samples.size(); ++i) {
        auto& top = column[i * column.size() / samples.size()];
        top = std::max(top, samples[i]);
    }
    return column;
}

// Rows of eighth blocks, `level` 0..1 of each column's height; `label` beside the top row.
void plot_columns(std::ostream& out, const std::vector<double>& levels, int height,
                  const std::string& label, std::size_t margin) {
    for (int row = height - 1; row >= 0; --row) {
        std::string line;
        for (const double level : levels) {
            const double eighths = std::clamp((level * height - row) * 8.0, 0.0, 8.0);
            line += kBlocks[static_cast<std::size_t>(std::lround(eighths))];
        }
        const std::string left = row == height - 1 ? label : "";
        out << left << std::string(margin - left.size(), ' ') << "│" << line << "\n";
    }
}

// The time axis under a chart of `width` columns, from 0 to `duration`.
void time_axis(std::ostream& out, int width, double duration, std::size_t margin) {
    out << std::string(margin, ' ') << "└";
    for (int i = 0; i < width; ++i) {
        out << "─";
    }
    const auto end = seconds(duration);
    out << "\n"
        << std::string(margin + 1, ' ') << "0"
        << std::string(
               static_cast<std::size_t>(std::max<int>(1, width - 1 - static_cast<int>(end.size()))),
               ' ')
        << end << "\n";
}

}  // namespace

void plot_envelope(std::ostream& out, const render::Performance& performance, int width,
                   int height) {
    width = std::max(width, 10);
    height = std::max(height, 1);
    const double duration = performance.duration();
    const double peak = performance.peak_amplitude();
    if (duration <= 0.0 || peak <= 0.0) {
        out << "(silent)\n";
        return;
    }
    const double rate = width * kSamplesPerColumn / duration;
    std::vector<double> samples(static_cast<std::size_t>(width) * kSamplesPerColumn);
    render::render_envelope(performance, rate, 0, samples);
    std::vector<double> column(static_cast<std::size_t>(width), 0.0);
    for (std::size_t i = 0; i < samples.size(); ++i) {
        auto& top = column[i / kSamplesPerColumn];
        top = std::max(top, samples[i] / peak);
    }
    plot_columns(out, column, height, "peak", 5);
    time_axis(out, width, duration, 5);
}

void plot_response(std::ostream& out, const render::ActuatorResponse& response, int width,
                   int height) {
    width = std::max(width, 10);
    height = std::max(height, 1);
    const std::size_t count = response.written.size();
    if (count == 0 || response.rate_hz <= 0.0) {
        out << "(silent)\n";
        return;
    }
    const auto written = column_peaks(response.written, width);
    const auto uncompensated = column_peaks(response.uncompensated, width);
    const auto compensated = column_peaks(response.compensated, width);
    double peak = 0.0;
    for (const auto* columns : {&written, &uncompensated, &compensated}) {
        peak = std::max(peak, *std::max_element(columns->begin(), columns->end()));
    }
    if (peak <= 0.0) {
        out << "(silent)\n";
        return;
    }
    constexpr std::size_t margin = 14;  // "uncompensated "
    char top[32];
    std::snprintf(top, sizeof top, "%.3g", peak);
    out << "strength, 1 = the rated drive; each chart from 0 to " << top << "\n";
    const auto scaled = [&](std::vector<double> columns) {
        for (auto& level : columns) {
            level /= peak;
        }
        return columns;
    };
    plot_columns(out, scaled(written), height, "written", margin);
    plot_columns(out, scaled(uncompensated), height, "uncompensated", margin);
    plot_columns(out, scaled(compensated), height, "compensated", margin);
    time_axis(out, width, static_cast<double>(count) / response.rate_hz, margin);
}

}  // namespace vibscore::client
