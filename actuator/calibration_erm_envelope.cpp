// An ERM's vibration envelope that does not depend on where the readings fall in the mass's turn.
//
// |vibration|^2 of a force along one axis is A^2 cos^2(angle): on a uniform clock the ripple at
// twice the rotation aliases to a steady frequency the moving average removes, but readings
// taken at jittered instants (±1 ms is ±0.4 of a turn at 200 Hz) sample cos^2 at random, and its
// spread (relative 0.35 per reading) is what limited the spin-up estimate at 400 Hz. Fitting
// the sinusoid itself, a cos(angle) + b sin(angle) at the readings' own times, gives A^2 =
// a^2 + b^2 whatever the phase: the angle comes from the rotation frequency at full speed
// (measured on the plateaus) and the speed a first fit predicts; a window of a few readings
// only needs that frequency locally right, not the angle's accumulated value.
//
// The vibration it is given went through high_pass (gravity out: each reading minus a triangle
// of its neighbours, itself weighing 1/9 at 400 Hz). On a uniform clock the neighbours give
// back what that takes out of a fast vibration; at jittered instants their phases scatter (the
// more the faster the mass turns: at 200 Hz read at 400 Hz, half of it is lost), so a third
// to a half of the self-term stays out, and the vibration looked 12 % weaker at full speed
// than at half speed: the energy grew slower than speed^4 and the spin-up read 4-9 % short
// (bench/calibrated_feel seed 33). The sinusoids go through the same high-pass at the same
// instants, so the fit models what it takes away.
//
// The sinusoids carry the force the speed model predicts (speed^2): what a window fits is then
// how much stronger the vibration is than the model says, nearly constant over a few
// milliseconds even where the force itself changes fast, and the envelope at a reading is that
// times the model's force there. With sinusoids of one amplitude, a window's fit was its mean
// amplitude (below the energy's mean wherever the force changes) and the high-pass took more
// from a changing amplitude than from theirs: every coast was timed short, 24 of 24, 1.2 % in
// the median at 400 Hz and 1.1 % at 1 kHz, and spin-ups up to 5.7 % wrong, each with a doubt of
// tenths of that (bench/calibrate seed 32; now 0.08 % and 0.05 % in the median, 0.45 % at worst).
// Where the model is wrong the window's factor is not constant, and the fit's next round
// follows it.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "actuator/calibration_fit.hpp"

namespace vibscore::actuator::calibration::fit {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// The rotation frequencies a phone ERM runs at full speed (3000-25000 rpm and some margin).
constexpr double kLowestHz = 40.0, kHighestHz = 450.0, kStepHz = 0.25;
// The plateau: where the first fit says the motor is within this of full speed.
constexpr double kPlateauSpeed = 0.97;
// A window whose phases barely separate sine from cosine is believed this little at least
// (never nothing: the fit's floor still needs the quiet stretches).
constexpr double kWeightFloor = 0.01;
// The least force a sinusoid carries (speed^2: a mass at 3 % of full speed), so a window where
// the model has the motor still keeps finite equations; its angle stands still there, and the
// high-pass takes its sinusoid out whole.
constexpr double kStillForce = 1e-3;

// The full-speed rotation frequency: the peak of the plateaus' spectra summed over axes and
// plateaus (each plateau's phase is its own: summed as powers).
double full_speed_hz(const std::vector<double>& t, const std::vector<Vec3>& x,
                     const std::vector<double>& speed) {
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (std::size_t k = 0; k < t.size(); ++k) {
        if (speed[k] < kPlateauSpeed) {
            continue;
        }
        if (!runs.empty() && runs.back().second == k) {
            runs.back().second = k + 1;
        } else {
            runs.push_back({k, k + 1});
        }
    }
    // The turns made by each reading at 1 Hz full speed: the plateaus still chirp (a spin-up of
    // 80 ms is at 98.5 % of full speed there on average), and a peak read as if they did not
    // lies that much low; the envelope's phase then drifts most at full speed and the spin-up
    // read 2 % short (bench/calibrated_feel seed 33: a 79.3 ms spin-up, a motor at 200 Hz).
    std::vector<double> turns(t.size(), 0.0);
    for (std::size_t k = 1; k < t.size(); ++k) {
        turns[k] =
            turns[k - 1] + (t[k] - t[k - 1]) * 0.5 * (std::abs(speed[k]) + std::abs(speed[k - 1]));
    }
    std::vector<double> power;
    for (double f = kLowestHz; f <= kHighestHz; f += kStepHz) {
        double p = 0.0;
        for (const auto& [begin, end] : runs) {
            for (int axis = 0; axis < 3; ++axis) {
                double re = 0.0, im = 0.0;
                for (std::size_t k = begin; k < end; ++k) {
                    const double phase = kTwoPi * f * (turns[k] - turns[begin]);
                    re += x[k][axis] * std::cos(phase);
                    im += x[k][axis] * std::sin(phase);
                }
                p += re * re + im * im;
            }
        }
        power.push_back(p);
    }
    const std::size_t peak =
        static_cast<std::size_t>(std::max_element(power.begin(), power.end()) - power.begin());
    double offset = 0.0;
    if (peak > 0 && peak + 1 < power.size()) {
        const double a = power[peak - 1], b = power[peak], c = power[peak + 1];
        const double d = a - 2.0 * b + c;
        offset = d < 0.0 ? 0.5 * (a - c) / d : 0.0;
    }
    return kLowestHz + (static_cast<double>(peak) + offset) * kStepHz;
}

}  // namespace

namespace {

ErmEnvelope envelope_at(double full_speed_hz, const std::vector<double>& t_s,
                        const std::vector<Vec3>& vibration, const std::vector<double>& speed,
                        int half, int high_pass_half) {
    ErmEnvelope out;
    const std::size_t n = t_s.size();
    out.full_speed_hz = full_speed_hz;
    // The angle: the rotation's frequency integrated over the readings' own times.
    std::vector<double> c(n), s(n), force(n);
    double angle = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        if (k > 0) {
            angle += kTwoPi * full_speed_hz * (t_s[k] - t_s[k - 1]) * 0.5 *
                     (std::abs(speed[k]) + std::abs(speed[k - 1]));
            angle = std::fmod(angle, kTwoPi);
        }
        force[k] = std::max(kStillForce, speed[k] * speed[k]);
        c[k] = force[k] * std::cos(angle);
        s[k] = force[k] * std::sin(angle);
    }
    if (high_pass_half > 0) {
        const std::vector<double> slow_c =
            box_smooth(box_smooth(c, high_pass_half), high_pass_half);
        const std::vector<double> slow_s =
            box_smooth(box_smooth(s, high_pass_half), high_pass_half);
        for (std::size_t k = 0; k < n; ++k) {
            c[k] -= slow_c[k];
            s[k] -= slow_s[k];
        }
    }
    // Prefix sums of the 2x2 normal equations' terms, shared by the axes, and of each axis's.
    std::vector<double> pcc(n + 1, 0.0), pcs(n + 1, 0.0), pss(n + 1, 0.0), pff(n + 1, 0.0);
    std::vector<Vec3> pxc(n + 1, Vec3{0.0, 0.0, 0.0}), pxs(n + 1, Vec3{0.0, 0.0, 0.0});
    for (std::size_t k = 0; k < n; ++k) {
        pcc[k + 1] = pcc[k] + c[k] * c[k];
        pcs[k + 1] = pcs[k] + c[k] * s[k];
        pss[k + 1] = pss[k] + s[k] * s[k];
        pff[k + 1] = pff[k] + force[k] * force[k];
        for (int axis = 0; axis < 3; ++axis) {
            pxc[k + 1][axis] = pxc[k][axis] + vibration[k][axis] * c[k];
            pxs[k + 1][axis] = pxs[k][axis] + vibration[k][axis] * s[k];
        }
    }
    out.envelope.assign(n, 0.0);
    out.weight.assign(n, kWeightFloor);
    double residual = 0.0, total = 0.0;
    const long count = static_cast<long>(n);
    for (long k = 0; k < count; ++k) {
        const long lo = std::max(0L, k - half), hi = std::min(count - 1, k + half) + 1;
        const double cc = pcc[hi] - pcc[lo], cs = pcs[hi] - pcs[lo], ss = pss[hi] - pss[lo];
        // The sinusoids' strength before the high-pass (cos^2 + sin^2 = 1 a reading, times the
        // force's square): what it takes out of them (all of a still or slowly turning mass's)
        // is weakness too.
        const double trace = high_pass_half > 0 ? pff[hi] - pff[lo] : cc + ss;
        // How well the window's phases tell sine from cosine: 1 when they spread round the
        // turn, 0 when they all fall on one line (aliased to zero or half the rate, or still).
        const double separation =
            trace > 0.0 ? std::clamp(4.0 * (cc * ss - cs * cs) / (trace * trace), 0.0, 1.0) : 0.0;
        // A little ridge keeps a degenerate window's answer finite; its weight says the rest.
        const double ridge = 1e-3 * trace;
        const double a11 = cc + ridge, a22 = ss + ridge, det = a11 * a22 - cs * cs;
        double amplitude2 = 0.0;
        for (int axis = 0; axis < 3; ++axis) {
            const double xc = pxc[hi][axis] - pxc[lo][axis], xs = pxs[hi][axis] - pxs[lo][axis];
            const double a = det > 0.0 ? (a22 * xc - cs * xs) / det : 0.0;
            const double b = det > 0.0 ? (a11 * xs - cs * xc) / det : 0.0;
            amplitude2 += a * a + b * b;
            const double fitted =
                a * c[static_cast<std::size_t>(k)] + b * s[static_cast<std::size_t>(k)];
            const double x = vibration[static_cast<std::size_t>(k)][axis];
            residual += (x - fitted) * (x - fitted);
            total += x * x;
        }
        // Half the amplitude squared: the same scale as the energy of a sinusoid.
        const double here = force[static_cast<std::size_t>(k)];
        out.envelope[static_cast<std::size_t>(k)] = 0.5 * amplitude2 * here * here;
        out.weight[static_cast<std::size_t>(k)] = std::max(kWeightFloor, separation);
    }
    out.explained = total > 0.0 ? 1.0 - residual / total : 0.0;
    return out;
}

}  // namespace

ErmEnvelope erm_envelope(const Plan& plan, const std::vector<double>& t_s,
                         const std::vector<Vec3>& vibration, const ErmFit& first, int half,
                         int high_pass_half) {
    const std::size_t n = t_s.size();
    if (n < 3) {
        return {};
    }
    const std::vector<double> speed =
        erm_speeds(plan, first.spin_up_s, first.spin_down_s, first.delay_s, t_s);
    // On a uniform clock the plateaus cannot tell the rotation from its mirror about half the
    // rate (rate - f): both fit them alike. While the speed changes they part (the mirror's
    // local frequency moves the wrong way), so the one whose envelope explains more is kept.
    const double peak = full_speed_hz(t_s, vibration, speed);
    ErmEnvelope best = envelope_at(peak, t_s, vibration, speed, half, high_pass_half);
    const double mirror = median_rate(t_s) - peak;
    if (mirror >= kLowestHz && mirror <= kHighestHz) {
        ErmEnvelope other = envelope_at(mirror, t_s, vibration, speed, half, high_pass_half);
        if (other.explained > best.explained) {
            best = std::move(other);
        }
    }
    return best;
}

}  // namespace vibscore::actuator::calibration::fit
