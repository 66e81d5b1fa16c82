// An LRA's resonance and decay from a recording of its probe.
//
// The model, block by block of the plan (a tone, or a ring-down): the reading along the
// vibration's axis is a slow line (gravity, the hand) + a sinusoid at the tone's frequency (the
// steady response; any amplitude and phase) + a free ring at the resonator's damped frequency
// decaying at gamma from the block's start (any amplitude and phase). For a linear resonator
// this is exact whatever state a block starts in and whatever phase convention the drive has;
// the amplitudes are linear least squares, and only the resonance, gamma and the plan's offset
// in the recording are searched. Every basis is evaluated at the readings' own times, so a
// resonance above half the sampling rate is fitted as itself, not as its alias; the tones'
// steady strengths (which peak at resonance) then tell it from its mirror image.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "actuator/calibration_fit.hpp"

namespace vibscore::actuator::calibration::fit {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMaxBasis = 6;
// Candidates whose residuals are within this factor fit the readings alike.
constexpr double kSameFit = 1.5;
// A resonance and its mirror closer than this (relative) are both taken: their middle.
constexpr double kMiddleApart = 0.018;

struct Block {
    double start_s;
    double amplitude;
    double frequency_hz;
    bool rings;  // some drive came before or is now: the resonator may be moving
};

std::vector<Block> blocks_of(const Plan& plan, double offset_s) {
    std::vector<Block> blocks;
    bool driven_before = false;
    for (const PlanRow& row : plan.rows) {
        const bool driven = row.amplitude != 0.0;
        if (!driven && !blocks.empty() && blocks.back().amplitude == 0.0) {
            continue;  // still undriven: the same free ring (or the same quiet)
        }
        driven_before = driven_before || driven;
        blocks.push_back({row.t_s + offset_s, row.amplitude, row.frequency_hz, driven_before});
    }
    return blocks;
}

// Least squares of one block, accumulated reading by reading.
struct Normal {
    int n = 0;
    double a[kMaxBasis][kMaxBasis]{};
    double b[kMaxBasis]{};
    double yy = 0.0;
    long count = 0;

    void add(const double* g, double y) {
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j <= i; ++j) {
                a[i][j] += g[i] * g[j];
            }
            b[i] += g[i] * y;
        }
        yy += y * y;
        ++count;
    }
    // The residual sum of squares, and the coefficients.
    double solve(double* coef) const {
        if (count == 0) {
            return 0.0;
        }
        double l[kMaxBasis][kMaxBasis]{};
        double trace = 0.0;
        for (int i = 0; i < n; ++i) {
            trace += a[i][i];
        }
        const double ridge = 1e-10 * trace / n + 1e-300;
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j <= i; ++j) {
                double s = a[i][j] + (i == j ? ridge : 0.0);
                for (int k = 0; k < j; ++k) {
                    s -= l[i][k] * l[j][k];
                }
                l[i][j] = i == j ? std::sqrt(std::max(s, 1e-300)) : s / l[j][j];
            }
        }
        double z[kMaxBasis];
        for (int i = 0; i < n; ++i) {
            double s = b[i];
            for (int k = 0; k < i; ++k) {
                s -= l[i][k] * z[k];
            }
            z[i] = s / l[i][i];
        }
        for (int i = n - 1; i >= 0; --i) {
            double s = z[i];
            for (int k = i + 1; k < n; ++k) {
                s -= l[k][i] * coef[k];
            }
            coef[i] = s / l[i][i];
        }
        double explained = 0.0;
        for (int i = 0; i < n; ++i) {
            explained += coef[i] * b[i];
        }
        return std::max(0.0, yy - explained);
    }
};

struct Tone {
    double amplitude;     // drive, -1..1
    double frequency_hz;  // drive
    double response;      // fitted steady peak acceleration
};

class Model {
  public:
    Model(const Plan& plan, const std::vector<double>& t_s, const std::vector<double>& y)
        : plan_(plan), t_(t_s), y_(y) {}

    // The residual of the whole recording under (f0, gamma, offset); with `tones`, the steady
    // responses; with `quiet`, the residual with no vibration at all.
    double rss(double f0, double gamma, double offset, std::vector<Tone>* tones = nullptr,
               double* quiet = nullptr) const {
        const std::vector<Block> blocks = blocks_of(plan_, offset);
        std::vector<Normal> normal(blocks.size()), slow(blocks.size());
        const double wd =
            kTwoPi * f0 * std::sqrt(std::max(0.0, 1.0 - std::pow(gamma / (kTwoPi * f0), 2.0)));
        for (std::size_t k = 0; k < t_.size(); ++k) {
            const double t = t_[k];
            std::size_t b = 0;
            // Blocks are few (15): a linear scan from the last is as fast as a search.
            while (b + 1 < blocks.size() && t >= blocks[b + 1].start_s) {
                ++b;
            }
            const Block& block = blocks[b];
            double g[kMaxBasis];
            int n = 0;
            g[n++] = 1.0;
            g[n++] = (t - block.start_s) * 10.0;  // per 100 ms: well scaled against the others
            if (block.amplitude != 0.0) {
                const double w = kTwoPi * block.frequency_hz;
                g[n++] = std::cos(w * t);
                g[n++] = std::sin(w * t);
            }
            if (block.rings) {
                const double envelope = std::exp(-gamma * std::max(0.0, t - block.start_s));
                g[n++] = envelope * std::cos(wd * t);
                g[n++] = envelope * std::sin(wd * t);
            }
            normal[b].n = n;
            normal[b].add(g, y_[k]);
            if (quiet) {
                slow[b].n = 2;
                slow[b].add(g, y_[k]);
            }
        }
        double total = 0.0;
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            double coef[kMaxBasis]{};
            total += normal[b].solve(coef);
            if (tones && blocks[b].amplitude != 0.0 && normal[b].count > 0) {
                tones->push_back(
                    {blocks[b].amplitude, blocks[b].frequency_hz, std::hypot(coef[2], coef[3])});
            }
            if (quiet) {
                double c2[kMaxBasis]{};
                *quiet += slow[b].solve(c2);
            }
        }
        return total;
    }

  private:
    const Plan& plan_;
    const std::vector<double>& t_;
    const std::vector<double>& y_;
};

// Steady response at drive frequency f relative to the one at resonance: of the mass's
// acceleration (`power` 2: what the phone feels when it feels the mass's reaction), velocity (1)
// or position (0: a phone that feels the spring's force).
double response_at(double f, double f0, double gamma, int power = 2) {
    const double w = kTwoPi * f, w0 = kTwoPi * f0;
    return std::pow(w / w0, power) * w0 * w0 /
           std::sqrt(std::pow(w0 * w0 - w * w, 2.0) + std::pow(2.0 * gamma * w, 2.0)) /
           (w0 / (2.0 * gamma));
}

// How far the tones' steady responses are from the resonance curve of (f0, gamma), relative;
// and the full-scale strength that scales the curve to them.
std::pair<double, double> tone_misfit(const std::vector<Tone>& tones, double f0, double gamma,
                                      int power = 2) {
    double mp = 0.0, pp = 0.0, mm = 0.0;
    for (const Tone& tone : tones) {
        const double p =
            std::abs(tone.amplitude) * response_at(tone.frequency_hz, f0, gamma, power);
        mp += tone.response * p;
        pp += p * p;
        mm += tone.response * tone.response;
    }
    if (!(pp > 0.0) || !(mm > 0.0)) {
        return {1.0, 0.0};
    }
    const double scale = mp / pp;
    double miss = 0.0;
    for (const Tone& tone : tones) {
        const double p =
            std::abs(tone.amplitude) * response_at(tone.frequency_hz, f0, gamma, power);
        miss += std::pow(tone.response - scale * p, 2.0);
    }
    return {std::sqrt(miss / mm), scale};
}

// The misfit of the curve shape that fits best: how the phone couples to the mass is the
// mounting's, and a mirror image must lose under every coupling, not just the one assumed.
double best_tone_misfit(const std::vector<Tone>& tones, double f0, double gamma) {
    double best = 1e300;
    for (const int power : {0, 1, 2}) {
        best = std::min(best, tone_misfit(tones, f0, gamma, power).first);
    }
    return best;
}

struct Point {
    double f0, gamma, offset, rss;
};

// `slack`: how far beyond the bounds the simplex may go (0: held to them).
Point refine(const Model& model, Point start, double low_hz, double high_hz, double slack = 0.02) {
    // A local grid first (the residual has narrow valleys in frequency), then the simplex.
    Point best = start;
    const double qs[] = {2.5, 3.5, 5, 7, 10, 14, 20, 28, 40, 56, 80, 110};
    for (int i = -12; i <= 12; ++i) {
        const double f = start.f0 * (1.0 + 0.0025 * i);
        if (f < low_hz || f > high_hz) {
            continue;
        }
        for (const double q : qs) {
            const double gamma = std::numbers::pi * f / q;
            const double r = model.rss(f, gamma, start.offset);
            if (r < best.rss) {
                best = {f, gamma, start.offset, r};
            }
        }
    }
    const auto cost = [&](const std::vector<double>& p) {
        const double f = p[0];
        if (f < low_hz * (1.0 - slack) || f > high_hz * (1.0 + slack) || std::abs(p[2]) > 0.08) {
            return 1e300;
        }
        return model.rss(f, std::exp(p[1]), p[2]);
    };
    const std::vector<double> found = minimise(cost, {best.f0, std::log(best.gamma), best.offset},
                                               {0.002 * best.f0, 0.15, 0.002}, 120);
    const double r = cost(found);
    if (r < best.rss) {
        best = {found[0], std::exp(found[1]), found[2], r};
    }
    return best;
}

}  // namespace

LraFit fit_lra(const Plan& plan, const std::vector<double>& t_s, const std::vector<double>& signal,
               double low_hz, double high_hz, double rate_hz) {
    const Model model(plan, t_s, signal);
    // Coarse: resonance in 0.5 % steps over the whole range, a few Q, no offset.
    Point best{0.5 * (low_hz + high_hz), 0.0, 0.0, 1e300};
    const double qs[] = {3, 4.5, 7, 10, 15, 22, 33, 50};
    for (double f = low_hz; f <= high_hz; f *= 1.005) {
        for (const double q : qs) {
            const double gamma = std::numbers::pi * f / q;
            const double r = model.rss(f, gamma, 0.0);
            if (r < best.rss) {
                best = {f, gamma, 0.0, r};
            }
        }
    }
    // The plan's offset in the recording (a recorder that started late, the drive's latency).
    for (double offset = -0.05; offset <= 0.0501; offset += 0.002) {
        const double r = model.rss(best.f0, best.gamma, offset);
        if (r < best.rss) {
            best.offset = offset;
            best.rss = r;
        }
    }
    best = refine(model, best, low_hz, high_hz);

    // Sampled slower than twice the resonance, f0 and rate - f0 fit the readings alike, and the
    // search above may settle on either, or between them where the two are a few hertz apart.
    // So each side of half the rate gets its own best (from the answer if it lies there, else
    // from its mirror), the search held to that side: otherwise it slides to the other, which
    // fits exactly as well.
    std::vector<Point> candidates{best};
    const double half = 0.5 * rate_hz;
    if (low_hz < half && half < high_hz) {
        const auto side_refine = [&](const Point& from, bool below) {
            const double side_low = below ? low_hz : half, side_high = below ? half : high_hz;
            double f = (from.f0 < half) == below ? from.f0 : rate_hz - from.f0;
            f = std::clamp(f, side_low, side_high);
            const Point start{f, from.gamma, from.offset, model.rss(f, from.gamma, from.offset)};
            return refine(model, start, side_low, side_high, 0.0);
        };
        const Point below = side_refine(best, true), above = side_refine(best, false);
        // On the sensor's uniform clock the mirror of the better side, with its decay and
        // offset, fits exactly as well: start the other side from there too, so a search that
        // stalled on one side does not decide.
        const bool below_better = below.rss <= above.rss;
        const Point again = side_refine(below_better ? below : above, !below_better);
        candidates.push_back(below_better ? below : above);
        const Point& other = below_better ? above : below;
        candidates.push_back(again.rss < other.rss ? again : other);
    }
    double least = 1e300;
    for (const Point& c : candidates) {
        least = std::min(least, c.rss);
    }
    // Candidates the readings cannot tell apart are told apart by the tones: their steady
    // strengths peak at the resonance, not at its mirror.
    struct Judged {
        Point point;
        double misfit;
        double scale;
        double rss;
        double quiet;
    };
    std::vector<Judged> judged;
    for (const Point& c : candidates) {
        if (c.rss > kSameFit * least) {
            continue;
        }
        std::vector<Tone> tones;
        double quiet = 0.0;
        const double r = model.rss(c.f0, c.gamma, c.offset, &tones, &quiet);
        judged.push_back({c, best_tone_misfit(tones, c.f0, c.gamma),
                          tone_misfit(tones, c.f0, c.gamma).second, r, quiet});
    }
    const auto chosen =
        std::min_element(judged.begin(), judged.end(),
                         [](const Judged& a, const Judged& b) { return a.misfit < b.misfit; });
    LraFit out;
    out.resonance_hz = chosen->point.f0;
    out.decay_per_s = chosen->point.gamma;
    out.offset_s = chosen->point.offset;
    out.rss = chosen->rss;
    out.vibration_ss = chosen->quiet;
    out.tone_misfit = chosen->misfit;
    out.full_scale = chosen->scale;
    // The rival: the best-explaining candidate on the other side of half the rate (its mirror),
    // which the readings explain as well and only the tones' strengths set apart.
    for (const Judged& j : judged) {
        const bool other_side = (j.point.f0 < half) != (out.resonance_hz < half);
        if (other_side && std::abs(j.point.f0 / out.resonance_hz - 1.0) > 0.002 &&
            (out.rival_hz == 0.0 || j.misfit < out.rival_misfit)) {
            out.rival_hz = j.point.f0;
            out.rival_misfit = j.misfit;
        }
    }
    // A resonance this close to half the sampling rate and its mirror image are a few hertz
    // apart, and the tones, a few per cent apart themselves, cannot tell which: between the two
    // the error is at most half their distance.
    if (out.rival_hz > 0.0 &&
        std::abs(out.rival_hz - out.resonance_hz) < kMiddleApart * out.resonance_hz) {
        out.resonance_hz = 0.5 * (out.rival_hz + out.resonance_hz);
        out.rival_middle = true;
    }
    out.samples = static_cast<double>(t_s.size());
    return out;
}

LraSpread lra_pair_spread(const Plan& plan, const std::vector<double>& t_s,
                          const std::vector<double>& signal, const LraFit& fit) {
    // Each tone with its ring-down, from its start to the next tone's.
    std::vector<double> starts;
    for (std::size_t i = 0; i < plan.rows.size(); ++i) {
        if (plan.rows[i].amplitude != 0.0) {
            starts.push_back(plan.rows[i].t_s + fit.offset_s);
        }
    }
    starts.push_back(plan.duration_s() + fit.offset_s + 1.0);
    std::vector<double> f0s, qs;
    for (std::size_t p = 0; p + 1 < starts.size(); ++p) {
        std::vector<double> t, y;
        for (std::size_t k = 0; k < t_s.size(); ++k) {
            if (t_s[k] >= starts[p] && t_s[k] < starts[p + 1]) {
                t.push_back(t_s[k]);
                y.push_back(signal[k]);
            }
        }
        if (t.size() < 40) {
            continue;
        }
        const Model model(plan, t, y);
        const auto cost = [&](const std::vector<double>& x) {
            return model.rss(fit.resonance_hz * std::exp(x[0]), fit.decay_per_s * std::exp(x[1]),
                             fit.offset_s);
        };
        const std::vector<double> found = minimise(cost, {0.0, 0.0}, {0.002, 0.1}, 80);
        f0s.push_back(found[0]);
        qs.push_back(found[0] - found[1]);  // Q = pi f0 / gamma
    }
    // The standard error of the pairs' mean, robustly: the median absolute deviation (one
    // pair's tone far from the resonance rings weakly and times it poorly; it must not decide).
    const auto spread = [](std::vector<double> v) {
        if (v.size() < 3) {
            return 1.0;
        }
        std::sort(v.begin(), v.end());
        const double median = v[v.size() / 2];
        std::vector<double> deviation;
        for (const double x : v) {
            deviation.push_back(std::abs(x - median));
        }
        std::sort(deviation.begin(), deviation.end());
        return 1.4826 * deviation[deviation.size() / 2] / std::sqrt(static_cast<double>(v.size()));
    };
    LraSpread out;
    out.pairs = static_cast<int>(f0s.size());
    out.resonance = spread(f0s);
    out.q = spread(qs);
    return out;
}

}  // namespace vibscore::actuator::calibration::fit
