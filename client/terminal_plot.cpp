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
    for (int row = height - 1; row >= 0; --row) {
        std::string line;
        for (const double level : column) {
            const double eighths = std::clamp((level * height - row) * 8.0, 0.0, 8.0);
            line += kBlocks[static_cast<std::size_t>(std::lround(eighths))];
        }
        out << (row == height - 1 ? "peak " : "     ") << "│" << line << "\n";
    }
    out << "     └";
    for (int i = 0; i < width; ++i) {
        out << "─";
    }
    const auto end = seconds(duration);
    out << "\n      0"
        << std::string(
               static_cast<std::size_t>(std::max<int>(1, width - 1 - static_cast<int>(end.size()))),
               ' ')
        << end << "\n";
}

}  // namespace vibscore::client
