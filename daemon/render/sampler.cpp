#include "daemon/render/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

namespace vibscore::render {

namespace {

// A rotating phasor stands in for sin() on steady sine tones; it is re-seeded from the exact
// phase this often so rounding never builds up beyond ~1e-13.
constexpr std::uint64_t kReseedInterval = 256;

enum class View { signal, envelope };

}  // namespace

std::uint64_t sample_index_at(double t, double rate) {
    const double k = std::ceil(t * rate);
    auto index = k <= 0.0 ? std::uint64_t{0} : static_cast<std::uint64_t>(k);
    // Rounding in t * rate may put k one off; settle it on the definition.
    while (index > 0 && static_cast<double>(index - 1) / rate >= t) {
        --index;
    }
    while (static_cast<double>(index) / rate < t) {
        ++index;
    }
    return index;
}

namespace {

void steady_sine(const Tone& tone, double rate, std::uint64_t begin, std::uint64_t end,
                 double* out) {
    const double step = 2.0 * M_PI * tone.frequency_start / rate;
    const std::complex<double> rotation(std::cos(step), std::sin(step));
    for (std::uint64_t k = begin; k < end;) {
        const double dt = static_cast<double>(k) / rate - tone.onset;
        const double cycles = tone.phase_cycles + tone.frequency_start * dt;
        const double angle = 2.0 * M_PI * (cycles - std::floor(cycles));
        std::complex<double> phasor(std::cos(angle), std::sin(angle));
        const std::uint64_t stop = std::min(end, k + kReseedInterval);
        for (; k < stop; ++k) {
            const double local = static_cast<double>(k) / rate - tone.onset;
            *out++ = Performance::amplitude(tone, local) * phasor.imag();
            phasor *= rotation;
        }
    }
}

void render(const Performance& performance, double rate, std::uint64_t first, std::span<double> out,
            View view) {
    std::fill(out.begin(), out.end(), 0.0);
    const std::uint64_t last = first + out.size();
    const auto& tones = performance.tones();
    auto index = performance.tone_index_at(static_cast<double>(first) / rate);
    for (auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(index, 0)); i < tones.size();
         ++i) {
        const Tone& tone = tones[i];
        const std::uint64_t begin = std::max(first, sample_index_at(tone.onset, rate));
        const std::uint64_t end = std::min(last, sample_index_at(tone.end(), rate));
        if (begin >= last) {
            break;
        }
        if (begin >= end) {
            continue;
        }
        double* target = out.data() + (begin - first);
        if (tone.kind == Tone::Kind::sine) {
            if (view == View::envelope) {
                for (std::uint64_t k = begin; k < end; ++k) {
                    const double dt = static_cast<double>(k) / rate - tone.onset;
                    *target++ = std::abs(Performance::amplitude(tone, dt));
                }
            } else if (tone.frequency_start == tone.frequency_end) {
                steady_sine(tone, rate, begin, end, target);
            } else {
                for (std::uint64_t k = begin; k < end; ++k) {
                    const double dt = static_cast<double>(k) / rate - tone.onset;
                    const double cycles = tone.phase_cycles + Performance::sine_cycles(tone, dt);
                    *target++ = Performance::amplitude(tone, dt) *
                                std::sin(2.0 * M_PI * (cycles - std::floor(cycles)));
                }
            }
            continue;
        }
        Performance::ShapeCursor cursor;
        for (std::uint64_t k = begin; k < end; ++k) {
            const double dt = static_cast<double>(k) / rate - tone.onset;
            const double y =
                Performance::amplitude(tone, dt) * performance.shape_level(tone, dt, cursor);
            *target++ = view == View::envelope ? std::abs(y) : y;
        }
    }
}

}  // namespace

void render_signal(const Performance& performance, double rate, std::uint64_t first,
                   std::span<double> out) {
    render(performance, rate, first, out, View::signal);
}

void render_envelope(const Performance& performance, double rate, std::uint64_t first,
                     std::span<double> out) {
    render(performance, rate, first, out, View::envelope);
}

}  // namespace vibscore::render
