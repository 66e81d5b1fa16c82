#include "daemon/render/fitting/clef_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "actuator/physics.hpp"
#include "common/number_text.hpp"
#include "daemon/render/waveform.hpp"
#include "score/limits.hpp"

namespace vibscore::render {

namespace {

// A wiggle that swings less than this share of full level is ripple, not a shape to follow.
constexpr double kLeastWiggleSwing = 0.05;
// The smoothed string: averaged on a fine grid, written back as this many segments.
constexpr std::size_t kSmoothGrid = 4096;
constexpr std::size_t kSmoothPoints = 256;

std::string kind_name(const actuator::Declaration& declaration) {
    return declaration.kind == actuator::Kind::lra ? "LRA" : "ERM";
}

// The strongest strength full drive gives anywhere: at resonance for an LRA.
double strongest_reachable(const actuator::Declaration& declaration) {
    return 1.0 / declaration.rated_drive;
}

// Numbers kept, except those beyond full drive, which become what full drive gives.
std::vector<double> fitted_numbers(const Clef& written, const actuator::Declaration& declaration,
                                   std::vector<std::string>& notes) {
    const double reachable = strongest_reachable(declaration);
    std::vector<double> numbers = written.numbers;
    for (std::size_t n = 0; n < numbers.size(); ++n) {
        if (numbers[n] > reachable) {
            notes.push_back(
                "number " + std::to_string(n + 1) + ": strength " + number_text(numbers[n]) +
                " is beyond full drive (" + fixed_text(reachable, 3) + " with rated-drive " +
                number_text(declaration.rated_drive) + "): " + fixed_text(reachable, 3));
            numbers[n] = reachable;
        }
    }
    return numbers;
}

double strongest_of(const std::vector<double>& numbers) {
    return numbers.empty() ? 0.0 : *std::max_element(numbers.begin(), numbers.end());
}

bool in_band(double f, const Band& band) {
    return f >= band.low_hz && f <= band.high_hz;
}

// The written strings can stay: each inside the band, neighbours distinct.
bool playable_as_written(const Clef& clef, const Band& band) {
    for (std::size_t s = 0; s < clef.strings.size(); ++s) {
        if (!in_band(clef.strings[s].frequency, band)) {
            return false;
        }
        if (s > 0) {
            const double a = clef.strings[s - 1].frequency, b = clef.strings[s].frequency;
            if (std::max(a, b) / std::min(a, b) < kDistinctPitchRatio) {
                return false;
            }
        }
    }
    return true;
}

// Square waves: drive for the first half of each period, none for the second.
ClefString square_wave(double period_s, double tempo_s, std::size_t string) {
    ClefString out;
    if (period_s <= 0.0) {
        out.points = {{0.0, 1.0}, {1.0, 1.0}};
        return out;
    }
    const double half = period_s / tempo_s / 2.0;
    const auto halves = static_cast<std::size_t>(std::ceil(1.0 / half - 1e-9));
    if (2 * halves > limits::points_per_string) {
        throw ClefFitError("string " + std::to_string(string) + ": a quarter note of " +
                           number_text(tempo_s) + " s holds " + std::to_string(halves / 2) +
                           " periods of " + ms_text(period_s) + ", more than the " +
                           std::to_string(limits::points_per_string) + " points a string may have");
    }
    for (std::size_t k = 0; k < halves; ++k) {
        const double level = k % 2 == 0 ? 1.0 : 0.0;
        const double start = static_cast<double>(k) * half;
        const double end = std::min(1.0, static_cast<double>(k + 1) * half);
        out.points.push_back({start, level});
        out.points.push_back({end, level});
    }
    return out;
}

// The string averaged over a window of `width` (normalised time), held at its ends.
ClefString smoothed(ClefType type, const ClefString& string, double width) {
    const Waveform waveform(type, string.points);
    std::vector<double> sums(kSmoothGrid + 2, 0.0);
    const double step = 1.0 / static_cast<double>(kSmoothGrid);
    for (std::size_t k = 0; k <= kSmoothGrid; ++k) {
        sums[k + 1] = sums[k] + std::clamp(waveform.level(static_cast<double>(k) * step), 0.0, 1.0);
    }
    const auto half = static_cast<std::ptrdiff_t>(std::round(width / 2.0 / step));
    const auto last = static_cast<std::ptrdiff_t>(kSmoothGrid);
    ClefString out;
    for (std::size_t p = 0; p <= kSmoothPoints; ++p) {
        const double t = static_cast<double>(p) / static_cast<double>(kSmoothPoints);
        const auto centre = static_cast<std::ptrdiff_t>(std::round(t / step));
        const auto from = std::max<std::ptrdiff_t>(0, centre - half);
        const auto to = std::min(last, centre + half);
        const double mean =
            (sums[static_cast<std::size_t>(to + 1)] - sums[static_cast<std::size_t>(from)]) /
            static_cast<double>(to - from + 1);
        out.points.push_back({t, std::clamp(mean, 0.0, 1.0)});
    }
    return out;
}

ClefFit roughness(const Clef& written, const actuator::Declaration& declaration, ClefFit fit,
                  const std::string& why) {
    const double strongest = strongest_of(fit.clef.numbers);
    fit.strings = ClefFit::Strings::roughness;
    fit.periods_s = roughness_periods_s(declaration, written.strings.size(), strongest);
    fit.clef.type = ClefType::line;
    fit.clef.strings.clear();
    std::string periods;
    for (std::size_t s = 0; s < written.strings.size(); ++s) {
        const double period = fit.periods_s.empty() ? 0.0 : fit.periods_s[s];
        fit.clef.strings.push_back(square_wave(period, written.tempo, s + 1));
        periods += (s > 0 ? ", " : "") + (period > 0.0 ? ms_text(period) : std::string("steady"));
    }
    fit.notes.push_back("strings: " + why + ": they become roughness at the " +
                        kind_name(declaration) + "'s own frequency, square-wave periods " +
                        periods + " (string 1 first)");
    return fit;
}

ClefFit fit_sine(const Clef& written, const actuator::Declaration& declaration, ClefFit fit) {
    const std::size_t n = written.strings.size();
    if (declaration.kind == actuator::Kind::erm) {
        return roughness(written, declaration, std::move(fit), "an ERM has no pitch to play");
    }
    const double strongest = strongest_of(fit.clef.numbers);
    const double wanted =
        declaration.compensation ? strongest : kUncompensatedGain / declaration.rated_drive;
    fit.band = full_strength_band(declaration, wanted);
    if (!fit.band) {
        return roughness(written, declaration, std::move(fit),
                         "the LRA gives strength " + fixed_text(wanted, 3) +
                             " at no frequency from " + hz_text(kLowestPitchHz) + " to " +
                             hz_text(kHighestPitchHz));
    }
    const Band band = *fit.band;
    const std::string band_text = hz_text(band.low_hz) + " to " + hz_text(band.high_hz);
    if (playable_as_written(written, band)) {
        for (const auto& string : written.strings) {
            fit.frequencies_hz.push_back(string.frequency);
        }
        return fit;
    }
    if (n == 1) {
        const double f = in_band(declaration.resonance_hz, band)
                             ? declaration.resonance_hz
                             : std::sqrt(band.low_hz * band.high_hz);
        fit.strings = ClefFit::Strings::pitch;
        fit.frequencies_hz = {f};
        fit.clef.strings[0].frequency = f;
        fit.notes.push_back("string 1: " + hz_text(written.strings[0].frequency) + " -> " +
                            hz_text(f) + " (full strength " + band_text + ")");
        return fit;
    }
    const double span = band.high_hz / band.low_hz;
    const double needed = std::pow(kDistinctPitchRatio, static_cast<double>(n - 1));
    if (span < needed) {
        return roughness(written, declaration, std::move(fit),
                         "full strength only " + band_text + " (ratio " + fixed_text(span, 2) +
                             "), too narrow for " + std::to_string(n) + " strings " +
                             number_text(kDistinctPitchRatio) + " apart (needs " +
                             fixed_text(needed, 2) + ")");
    }
    // Spread across the band geometrically, keeping the written order of pitch.
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return written.strings[a].frequency < written.strings[b].frequency;
    });
    const double ratio = std::pow(span, 1.0 / static_cast<double>(n - 1));
    fit.strings = ClefFit::Strings::pitch;
    fit.frequencies_hz.assign(n, 0.0);
    for (std::size_t rank = 0; rank < n; ++rank) {
        fit.frequencies_hz[order[rank]] = band.low_hz * std::pow(ratio, static_cast<double>(rank));
    }
    fit.frequencies_hz[order[n - 1]] = band.high_hz;  // exactly, not by rounding of the powers
    std::string moves;
    for (std::size_t s = 0; s < n; ++s) {
        fit.clef.strings[s].frequency = fit.frequencies_hz[s];
        moves += (s > 0 ? ", " : "") + hz_text(written.strings[s].frequency) + " -> " +
                 hz_text(fit.frequencies_hz[s]);
    }
    fit.notes.push_back("strings: full strength " + band_text + ", strings spread " +
                        fixed_text(ratio, 2) + " apart: " + moves);
    return fit;
}

ClefFit fit_shape(const Clef& written, const actuator::Declaration& declaration, ClefFit fit) {
    const double strongest = strongest_of(fit.clef.numbers);
    const double follows = shortest_followed_s(declaration, strongest);
    if (!std::isfinite(follows)) {
        return fit;
    }
    for (std::size_t s = 0; s < written.strings.size(); ++s) {
        const auto wiggle = shortest_wiggle(written.strings[s]);
        if (!wiggle || *wiggle * written.tempo >= follows) {
            continue;
        }
        fit.strings = ClefFit::Strings::smoothed;
        fit.clef.strings[s] = smoothed(written.type, written.strings[s], follows / written.tempo);
        fit.notes.push_back("string " + std::to_string(s + 1) + ": a " +
                            ms_text(*wiggle * written.tempo) + " rise or fall is faster than the " +
                            kind_name(declaration) + " follows (" + ms_text(follows) +
                            "): smoothed over " + ms_text(follows));
    }
    return fit;
}

}  // namespace

std::optional<Band> full_strength_band(const actuator::Declaration& declaration, double strength) {
    if (declaration.kind != actuator::Kind::lra) {
        return std::nullopt;
    }
    const double f0 = declaration.resonance_hz;
    const double g = strength * declaration.rated_drive;  // the gain full drive needs
    Band band{kLowestPitchHz, kHighestPitchHz};
    if (g > 0.0) {
        const auto reaching = actuator::Physics::lra_band(g, f0, declaration.q);
        if (!reaching) {
            return std::nullopt;
        }
        band.low_hz = std::max(band.low_hz, reaching->low_hz);
        band.high_hz = std::min(band.high_hz, reaching->high_hz);
    }
    if (band.low_hz > band.high_hz) {
        return std::nullopt;
    }
    return band;
}

double time_to_strength_s(const actuator::Declaration& declaration, double strength) {
    const actuator::Physics physics(declaration);
    const double amplitude = declaration.compensation ? 1.0 : declaration.rated_drive;
    const double level = declaration.compensation ? strength : 0.9 * strength;
    const actuator::Drive drive{amplitude, 0.0};
    if (!(level > 0.0)) {
        return 0.0;
    }
    if (physics.steady_strength(drive) <= level) {
        return std::numeric_limits<double>::infinity();
    }
    const auto reach = physics.time_to({}, drive, level, 60.0);
    return reach.outcome == actuator::Physics::Reach::Outcome::reached
               ? reach.after_s
               : std::numeric_limits<double>::infinity();
}

double shortest_followed_s(const actuator::Declaration& declaration, double strongest) {
    return time_to_strength_s(declaration, 0.5 * strongest);
}

std::vector<double> roughness_periods_s(const actuator::Declaration& declaration,
                                        std::size_t strings, double strongest) {
    if (strings <= 1) {
        return {};
    }
    const double reach = time_to_strength_s(declaration, strongest);
    const double shortest = std::isfinite(reach) ? 2.0 * reach : kSmoothestPeriodS;
    std::vector<double> periods(strings);
    const double steps = static_cast<double>(strings - 1);
    for (std::size_t s = strings; s-- > 0;) {
        const double thesis = kRoughestPeriodS - (kRoughestPeriodS - kSmoothestPeriodS) *
                                                     static_cast<double>(s) / steps;
        const double floor = s + 1 == strings ? shortest : periods[s + 1] * kDistinctPitchRatio;
        // Lengthened periods are whole milliseconds, so a fitted clef reads as written by hand.
        periods[s] = floor > thesis ? std::ceil(floor * 1000.0 - 1e-9) / 1000.0 : thesis;
    }
    return periods;
}

std::optional<double> shortest_wiggle(const ClefString& string) {
    struct Run {
        int direction = 0;
        double duration = 0.0, swing = 0.0;
        bool step = false;
    };
    std::vector<Run> runs;
    const auto& points = string.points;
    for (std::size_t p = 1; p < points.size(); ++p) {
        const double rise = points[p].level - points[p - 1].level;
        const double duration = points[p].time - points[p - 1].time;
        const int direction = rise > 0.0 ? 1 : (rise < 0.0 ? -1 : 0);
        if (runs.empty() || runs.back().direction != direction || direction == 0) {
            runs.push_back({direction, 0.0, 0.0, false});
        }
        runs.back().duration += duration;
        runs.back().swing += std::abs(rise);
        runs.back().step = runs.back().step || (duration == 0.0 && direction != 0);
    }
    std::optional<double> shortest;
    for (std::size_t r = 1; r < runs.size(); ++r) {
        const Run& a = runs[r - 1];
        const Run& b = runs[r];
        if (a.direction == 0 || b.direction != -a.direction || a.step || b.step ||
            std::min(a.swing, b.swing) < kLeastWiggleSwing) {
            continue;
        }
        const double half = std::min(a.duration, b.duration);
        shortest = shortest ? std::min(*shortest, half) : half;
    }
    return shortest;
}

ClefFit fit_clef(const Clef& written, const actuator::Declaration& declaration) {
    ClefFit fit;
    fit.clef = written;
    fit.clef.numbers = fitted_numbers(written, declaration, fit.notes);
    if (written.type == ClefType::sine) {
        return fit_sine(written, declaration, std::move(fit));
    }
    return fit_shape(written, declaration, std::move(fit));
}

std::string_view to_string(ClefFit::Strings strings) {
    switch (strings) {
        case ClefFit::Strings::as_written:
            return "as written";
        case ClefFit::Strings::pitch:
            return "pitch";
        case ClefFit::Strings::roughness:
            return "roughness";
        case ClefFit::Strings::smoothed:
            return "smoothed";
    }
    return "?";
}

}  // namespace vibscore::render
