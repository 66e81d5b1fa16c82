// estimate(): what a recording of a probe says about the actuator, and whether to trust it;
// apply() and declaration_lines(): what a trusted estimate changes; the pictures' traces.
#include "actuator/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

#include "actuator/calibration_fit.hpp"
#include "actuator/physics.hpp"
#include "common/number_text.hpp"

namespace vibscore::actuator::calibration {

namespace {

using fit::Vec3;

// Fewer readings than this cannot hold a probe: a recorder that stopped, or the wrong file.
constexpr std::size_t kMinSamples = 200;
// The vibration must stand this far above the readings' noise: below, the phone is not feeling
// the actuator (no contact, a soft surface, the wrong sensor).
constexpr double kMinSnrDb = 12.0;
// What the model may leave of the vibration: more, and it is not describing this actuator.
constexpr double kMaxLraResidual = 0.35;
constexpr double kMaxErmResidual = 0.6;
// LRA: the search reaches this far beyond the probe's tones; an answer at its edge is refused.
constexpr double kLraSearchMargin = 1.12;
constexpr double kMinQ = 2.0, kMaxQ = 150.0;
// ERM: what the probe's steps can time (0.35 s on, 0.55 s off).
constexpr double kMinSpinS = 0.006, kMaxSpinUpS = 0.2, kMaxSpinDownS = 0.4;
// Clipping: this share of one axis's readings (and at least 5) at exactly its extreme value,
// far from its median. A vibration's own peaks put a few readings on the top quantisation
// step; a clipped one piles a good share of them there.
constexpr double kClippedShare = 0.01;
// ERM: the phase-coherent envelope is used when its local sinusoids explain at least this share
// of the vibration (a steadily turning mass); below, the energy fit stands.
constexpr double kMinEnvelopeExplained = 0.5;
// ... and when the reported times explain this much more than the sensor's uniform clock would.
constexpr double kJitteredMargin = 0.02;
// ... fitted this many times, each on the envelope the previous answer's speed predicts.
constexpr int kEnvelopeRounds = 3;
// ERM: the fastest a phone's motor turns (issue 32: 100-250 Hz at full speed), with a margin.
constexpr double kMaxRotationHz = 300.0;
// ... and how one-sided its force must be (the energy's ripple, 0..1) for the stretch where the
// ripple aliases to zero to be left out of the fit.
constexpr double kMinBlindRipple = 0.5;
// LRA: the tones rule out the resonance's mirror image only where its misfit is at least this
// many times the chosen curve's (bench/calibrate seed 7 at 400 Hz, every sensor variant: the
// mirror of a right answer left 4.7-400 times its misfit).
constexpr double kToneVerdict = 3.0;

// The high-pass that takes gravity and the hand out of the readings (fit::high_pass): about
// 10 ms on either side.
int high_pass_half(double rate_hz) {
    return std::max(1, static_cast<int>(std::lround(0.010 * rate_hz)));
}

// The same for an ERM's energy: about 40 ms on either side. A coasting motor slows through the
// band the short one takes out (at a quarter of 100 Hz it turns at 25 Hz, and keeps 0.63 of its
// swing; through this one 1.00), so the end of every coast looked quieter than it was:
// spin-downs read 1-3 % short and spin-ups up to 2 %, with a stated doubt of hundredths of a
// per cent (bench/calibrate at 1 kHz without noise or delay: spin-downs 1.4 % short in the
// median, 2.9 % at worst; 0.14 % and 0.29 % with this one). Gravity is still taken out whole;
// a hand's movement of a few hertz less so, and the calibration asks for the phone on a hard
// surface anyway. The phase-coherent envelope of readings at jittered instants keeps the short
// one (tried: a 17 % miss at 400 Hz).
int erm_energy_high_pass_half(double rate_hz) {
    return std::max(1, static_cast<int>(std::lround(0.040 * rate_hz)));
}

double axis_of(const Sample& s, int axis) {
    return axis == 0 ? s.x : axis == 1 ? s.y : s.z;
}

std::string text(double value, int digits = 3) {
    return rounded_text(value, digits);
}

double first_drive_s(const Plan& plan) {
    for (const PlanRow& row : plan.rows) {
        if (row.amplitude != 0.0) {
            return row.t_s;
        }
    }
    return plan.duration_s();
}

bool clipped(const std::vector<Sample>& samples, std::string& which) {
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> v;
        v.reserve(samples.size());
        for (const Sample& s : samples) {
            v.push_back(axis_of(s, axis));
        }
        const double high = *std::max_element(v.begin(), v.end());
        const double low = *std::min_element(v.begin(), v.end());
        std::vector<double> sorted = v;
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        const double median = sorted[sorted.size() / 2];
        for (const double extreme : {high, low}) {
            const auto at = std::count(v.begin(), v.end(), extreme);
            if (at >= 5 && static_cast<double>(at) >= kClippedShare * v.size() &&
                std::abs(extreme - median) > 1.0) {
                which = std::string(1, static_cast<char>('x' + axis)) + " at " + text(extreme, 4) +
                        " m/s² (" + std::to_string(at) + " readings)";
                return true;
            }
        }
    }
    return false;
}

void set_unmeasured(Estimate& e, const std::string& why) {
    if (e.kind == Kind::erm) {
        e.unmeasured.push_back(std::string(kSpinUpMs.key) + ": " + why);
        e.unmeasured.push_back(std::string(kSpinDownMs.key) + ": " + why);
    } else {
        e.unmeasured.push_back(std::string(kResonanceHz.key) + ": " + why);
        e.unmeasured.push_back(std::string(kQ.key) + ": " + why);
    }
}

void check_limit(Estimate& e, const Limit& limit, double value) {
    if (value < limit.min || value > limit.max || (!limit.min_allowed && value == limit.min)) {
        e.problems.push_back(std::string("the measured ") + limit.key + " " + text(value, 4) +
                             " is outside what a declaration allows (" + text(limit.min, 4) + ".." +
                             text(limit.max, 4) + ")");
    }
}

// The noise the vibration is compared with: what the readings do before the first drive.
double quiet_power(const std::vector<double>& t, const std::vector<Vec3>& vibration,
                   double before_s) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
        if (t[k] < before_s) {
            sum += vibration[k][0] * vibration[k][0] + vibration[k][1] * vibration[k][1] +
                   vibration[k][2] * vibration[k][2];
            ++count;
        }
    }
    return count >= 10 ? sum / count : -1.0;
}

void estimate_lra(Estimate& e, const Plan& plan, const std::vector<Sample>& samples,
                  const std::vector<Vec3>& vibration, const std::vector<double>& raw,
                  const std::optional<Declaration>& nominal) {
    const LraRange range = lra_range(nominal);
    const double low = range.low_hz / kLraSearchMargin, high = range.high_hz * kLraSearchMargin;
    // The vibration's axis from the driven part; the reading along it (gravity included: each
    // block's slow line takes it).
    const Vec3 axis = fit::principal_axis(vibration);
    std::vector<double> y(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
        y[k] = samples[k].x * axis[0] + samples[k].y * axis[1] + samples[k].z * axis[2];
    }
    // Reported times jitter either because the readings were taken at jittered instants (then
    // the reported times are right) or because the report is late by a varying amount (then
    // the sensor's uniform clock is): fit both ways and keep the one that explains more.
    const std::vector<double> regular = fit::regular_times(raw);
    fit::LraFit best;
    bool first = true;
    const std::vector<double>* best_times = &regular;
    for (const std::vector<double>* times : {&regular, &raw}) {
        const fit::LraFit f = fit::fit_lra(plan, *times, y, low, high, e.sample_rate_hz);
        if (first || f.rss < best.rss) {
            best = f;
            best_times = times;
            first = false;
        }
    }
    const fit::LraSpread pairs = fit::lra_pair_spread(plan, *best_times, y, best);
    // Sampled slower than twice the resonance, the readings cannot tell it from its mirror
    // image about half the rate: only the tones' strengths can, and only where the mirror's
    // misfit stands clearly above what the chosen curve leaves (the tones' noise, a coupling or
    // sensor slope the curve does not model). Otherwise the answer may be either, and twice
    // the uncertainty reaches the other; where the middle of the two was taken, half-way.
    double mirror_doubt = 0.0;
    if (best.rival_hz > 0.0 &&
        (best.rival_middle || best.rival_misfit < kToneVerdict * best.tone_misfit)) {
        mirror_doubt = 0.5 * std::abs(std::log(best.rival_hz / best.resonance_hz));
        e.mirror_hz = best.rival_hz;
    }
    e.resonance_uncertainty = std::hypot(pairs.resonance, mirror_doubt);
    e.q_uncertainty = pairs.q;
    e.resonance_hz = best.resonance_hz;
    e.q = std::numbers::pi * best.resonance_hz / best.decay_per_s;
    e.full_scale_accel = best.full_scale;
    e.residual = best.vibration_ss > 0.0 ? std::sqrt(best.rss / best.vibration_ss) : 1.0;
    // Signal: what the vibration's terms explain, per reading; noise: what one axis does
    // before the first drive (or, without a quiet stretch, what the fit leaves).
    double noise = quiet_power(raw, vibration, first_drive_s(plan) + best.offset_s - 0.025) / 3.0;
    if (noise < 0.0) {
        noise = best.rss / std::max(1.0, best.samples);
    }
    const double signal = (best.vibration_ss - best.rss) / std::max(1.0, best.samples);
    e.snr_db = 10.0 * std::log10(std::max(signal, 1e-30) / std::max(noise, 1e-30));
    if (e.snr_db < kMinSnrDb) {
        return;  // the caller refuses it for that; the numbers below would be noise
    }
    if (best.resonance_hz <= low * 1.01 || best.resonance_hz >= high / 1.01) {
        e.problems.push_back("the resonance came out at the edge of what the probe covers (" +
                             text(low, 4) + "-" + text(high, 4) +
                             " Hz): declare a resonance-hz nearer the part's datasheet value and "
                             "calibrate again");
    }
    if (*e.q <= kMinQ * 1.02 || *e.q >= kMaxQ / 1.02) {
        e.problems.push_back("the quality factor came out at " + text(*e.q) +
                             ", beyond what the probe can measure (" + text(kMinQ) + "-" +
                             text(kMaxQ) + ")");
    }
    if (best.tone_misfit > kMaxLraResidual) {
        e.problems.push_back("the tones' strengths do not follow one resonance (misfit " +
                             text(best.tone_misfit, 2) +
                             "): the actuator or its mounting is not behaving as a resonator; "
                             "hold the phone still, or lay it on a hard surface, and try again");
    }
    check_limit(e, kResonanceHz, best.resonance_hz);
    check_limit(e, kQ, *e.q);
}

// `vibration` is the readings through high_pass_half's high-pass, `spinning` through
// erm_energy_high_pass_half's.
void estimate_erm(Estimate& e, const Plan& plan, const std::vector<Vec3>& vibration,
                  const std::vector<Vec3>& spinning, const std::vector<double>& raw) {
    std::vector<double> energy(spinning.size());
    for (std::size_t k = 0; k < spinning.size(); ++k) {
        energy[k] = spinning[k][0] * spinning[k][0] + spinning[k][1] * spinning[k][1] +
                    spinning[k][2] * spinning[k][2];
    }
    // A few milliseconds: several turns of the mass at speed, short against the time constants.
    const int half = std::max(1, static_cast<int>(std::lround(0.004 * e.sample_rate_hz)));
    const double length = 2.0 * half + 1.0;
    // Where the force is one-sided (along one axis, or an ellipse), |vibration|^2 has a ripple at
    // twice the rotation; the moving average removes it unless the sampling aliases it near
    // zero (the mass turning near a multiple of half the sampling rate: 200 Hz at 400 Hz).
    // Those stretches are believed less: the ripple's share comes from the spread of the
    // vibration across axes, its frequency from the readings' correlation with their
    // neighbours (cos of the phase step between readings).
    const Vec3 spread = fit::principal_spread(vibration);
    const double ripple =
        spread[0] + spread[1] > 0.0 ? (spread[0] - spread[1]) / (spread[0] + spread[1]) : 1.0;
    std::vector<double> lag(vibration.size(), 0.0), power(vibration.size(), 0.0);
    for (std::size_t k = 1; k + 1 < vibration.size(); ++k) {
        for (int i = 0; i < 3; ++i) {
            lag[k] += vibration[k][i] * (vibration[k - 1][i] + vibration[k + 1][i]);
            power[k] += 2.0 * vibration[k][i] * vibration[k][i];
        }
    }
    lag = fit::box_smooth(lag, 4 * half);
    power = fit::box_smooth(power, 4 * half);
    energy = fit::box_smooth(energy, half);
    // What else the energy carries (the noise of a sampled phase, the model's own roughness),
    // relative to it: the ripple's weight never outweighs it by more than ~100 times.
    constexpr double kWeightFloor = 0.1;
    std::vector<double> weight(energy.size());
    for (std::size_t k = 0; k < energy.size(); ++k) {
        const double cosine = power[k] > 0.0 ? std::clamp(lag[k] / power[k], -1.0, 1.0) : 0.0;
        const double rho = std::acos(cosine) / std::numbers::pi;  // ripple, cycles per reading
        const double s = std::sin(std::numbers::pi * rho);
        const double kept = std::abs(s) > 1e-9
                                ? std::abs(std::sin(std::numbers::pi * rho * length) / (length * s))
                                : 1.0;
        // Relative to the energy, as the least squares of the energy itself weigh every reading
        // alike where no ripple is left.
        const double wobble = ripple * kept;
        weight[k] = 1.0 / (kWeightFloor * kWeightFloor + wobble * wobble);
    }
    const std::vector<double> regular = fit::regular_times(raw);
    const int passed = high_pass_half(e.sample_rate_hz);
    fit::ErmFit best;
    bool first = true;
    std::vector<fit::ErmFit> fits;
    const std::vector<double>* best_times = &regular;
    for (const std::vector<double>* times : {&regular, &raw}) {
        fits.push_back(fit::fit_erm(plan, *times, energy, weight, half));
        if (first || fits.back().rss < best.rss) {
            best = fits.back();
            best_times = times;
            first = false;
        }
    }
    // A force along one axis: its energy's ripple (twice the rotation) aliases to zero where
    // the rotation passes half the sampling rate, and there the average keeps it, for ~20 ms
    // of a fast spin-up; the steps share the bias (bench/calibrate seed 101: motors at
    // 230-243 Hz read at 400 Hz, spin-ups of 22 ms timed 16-28 % slow). The fitted speed and
    // the rotation at full speed (the plateaus' spectrum; and its mirror about half the rate
    // if a phone's motor could turn that fast) say which readings fall there: the fit is made
    // again without them, and half of what that moved is doubt.
    // Where the fit kept a sensor low-pass, the answer stays the one with every reading: those
    // near half the rate are where such a filter shows most, and without them it is not told
    // from a slower motor (tried: through a filter at 400 Hz, twice the refusals and misses of
    // 17-18 % on seeds 11 and 32). What leaving them out moves is doubt all the same (seed 11:
    // a motor at 236 Hz through a filter at 100 Hz, trusted 15.1 % short at ±13 %).
    double blind_up = 0.0, blind_down = 0.0;
    const bool filtered = best.filter > 0.0;
    if (ripple > kMinBlindRipple) {
        const int window = std::max(3, static_cast<int>(std::lround(0.005 * e.sample_rate_hz)));
        const double full_speed_hz =
            fit::erm_envelope(plan, regular, vibration, fits[0], window, passed).full_speed_hz;
        std::vector<double> rotations{full_speed_hz};
        if (e.sample_rate_hz - full_speed_hz <= kMaxRotationHz) {
            rotations.push_back(e.sample_rate_hz - full_speed_hz);
        }
        // Where the ripple lies closer to zero than the average's own width removes.
        const double band = e.sample_rate_hz / (2.0 * length);
        std::vector<double> seen = weight;
        bool blind = false;
        const std::vector<double> speeds =
            fit::erm_speeds(plan, best.spin_up_s, best.spin_down_s, best.delay_s, *best_times);
        for (std::size_t k = 0; k < seen.size(); ++k) {
            const double speed = std::abs(speeds[k]);
            for (const double rotation : rotations) {
                if (full_speed_hz > 0.0 &&
                    std::abs(rotation * speed - 0.5 * e.sample_rate_hz) < band) {
                    seen[k] = 0.0;
                    blind = true;
                }
            }
        }
        if (blind) {
            const fit::ErmFit sighted = fit::fit_erm(plan, *best_times, energy, seen, half);
            blind_up = 0.5 * std::abs(std::log(sighted.spin_up_s / best.spin_up_s));
            blind_down = 0.5 * std::abs(std::log(sighted.spin_down_s / best.spin_down_s));
            if (!filtered) {
                best = sighted;
                weight = std::move(seen);
            }
        }
    }
    fit::ErmSpread steps = fit::erm_burst_spread(plan, *best_times, energy, weight, half, best);
    steps.spin_up = std::hypot(steps.spin_up, blind_up);
    steps.spin_down = std::hypot(steps.spin_down, blind_down);
    fit::ErmFit used = best;
    double spin_up_s = best.spin_up_s, spin_down_s = best.spin_down_s;
    // Readings taken at jittered instants (the reported times right, not the sensor's uniform
    // clock) sample the ripple of |vibration|^2 at random: there the time constants come from
    // the phase-coherent envelope. Which time base is right shows in how much of the vibration
    // the local sinusoids explain on each. On a uniform clock the energy fit stands: its ripple
    // aliases to a frequency the average removes, where the envelope's local frequency would
    // meet the same alias as the speed changes and mislead it.
    const int window = std::max(3, static_cast<int>(std::lround(0.005 * e.sample_rate_hz)));
    const fit::ErmEnvelope on_regular =
        fit::erm_envelope(plan, regular, vibration, fits[0], window, passed);
    const fit::ErmEnvelope on_raw =
        fit::erm_envelope(plan, raw, vibration, fits[1], window, passed);
    if (on_raw.explained >= kMinEnvelopeExplained &&
        on_raw.explained > on_regular.explained + kJitteredMargin) {
        // The envelope's sinusoids follow the rotation's phase that a speed model predicts,
        // first the energy fit's (noisy on such readings: up to 18 % off). A phase that drifts
        // from the truth within a window weakens the envelope there, so the answer leans on the
        // model it started from: it is fitted again on the envelope its own answer predicts,
        // until the two agree (bench/calibrate seed 7: a motor at 174 Hz timed 72.2 ms went
        // 89.5 -> 83.8 -> 76.3 -> 72.0 ms). What the last round still moved is doubt.
        fit::ErmEnvelope envelope = on_raw;
        fit::ErmFit coherent = fit::fit_erm(plan, raw, envelope.envelope, envelope.weight, window,
                                            fit::ErmTrace::coherent_envelope);
        double moved_up = 0.0, moved_down = 0.0;
        for (int round = 1; round < kEnvelopeRounds; ++round) {
            fit::ErmEnvelope next =
                fit::erm_envelope(plan, raw, vibration, coherent, window, passed);
            const fit::ErmFit refit = fit::fit_erm(plan, raw, next.envelope, next.weight, window,
                                                   fit::ErmTrace::coherent_envelope);
            moved_up = std::abs(std::log(refit.spin_up_s / coherent.spin_up_s));
            moved_down = std::abs(std::log(refit.spin_down_s / coherent.spin_down_s));
            coherent = refit;
            envelope = std::move(next);
        }
        spin_up_s = coherent.spin_up_s;
        spin_down_s = coherent.spin_down_s;
        steps = fit::erm_burst_spread(plan, raw, envelope.envelope, envelope.weight, window,
                                      coherent, fit::ErmTrace::coherent_envelope);
        steps.spin_up = std::hypot(steps.spin_up, moved_up);
        steps.spin_down = std::hypot(steps.spin_down, moved_down);
        used = coherent;
    }
    e.spin_up_s = spin_up_s;
    e.spin_down_s = spin_down_s;
    // Two doubts, independent: what sets the probe's steps apart, and what the answer leans on
    // a sensor low-pass whose form is guessed.
    e.spin_up_uncertainty = std::hypot(steps.spin_up, used.filter_doubt_up);
    e.spin_down_uncertainty = std::hypot(steps.spin_down, used.filter_doubt_down);
    // Peak of one axis's sinusoid with the same energy: what an LRA's figure means too.
    e.full_scale_accel = std::sqrt(2.0 * std::max(0.0, best.scale));
    e.residual = best.energy_ss > 0.0 ? std::sqrt(best.rss / best.energy_ss) : 1.0;
    double noise = quiet_power(raw, vibration, first_drive_s(plan) + best.delay_s - 0.025);
    if (noise < 0.0) {
        noise = best.floor;
    }
    e.snr_db = 10.0 * std::log10(std::max(best.scale, 1e-30) / std::max(noise, 1e-30));
    if (e.snr_db < kMinSnrDb) {
        return;
    }
    if (spin_up_s <= kMinSpinS || spin_up_s >= kMaxSpinUpS) {
        e.problems.push_back("the spin-up time came out at " + text(spin_up_s * 1000.0) +
                             " ms, beyond what the probe can time (" + text(kMinSpinS * 1000.0) +
                             "-" + text(kMaxSpinUpS * 1000.0) + " ms)");
    }
    if (spin_down_s <= kMinSpinS || spin_down_s >= kMaxSpinDownS) {
        e.problems.push_back("the spin-down time came out at " + text(spin_down_s * 1000.0) +
                             " ms, beyond what the probe can time (" + text(kMinSpinS * 1000.0) +
                             "-" + text(kMaxSpinDownS * 1000.0) + " ms)");
    }
    check_limit(e, kSpinUpMs, spin_up_s * 1000.0);
    check_limit(e, kSpinDownMs, spin_down_s * 1000.0);
    e.low_pass_doubt = std::max(used.filter_doubt_up, used.filter_doubt_down) >
                       std::max(steps.spin_up, steps.spin_down);
}

}  // namespace

Estimate estimate(const Plan& plan, const std::vector<Sample>& samples,
                  const std::optional<Declaration>& nominal) {
    Estimate e;
    e.kind = plan.kind;
    if (samples.size() < kMinSamples) {
        e.problems.push_back("the recording has " + std::to_string(samples.size()) +
                             " readings, too few for a probe of " + text(plan.duration_s()) +
                             " s: check that the accelerometer was recording throughout");
        set_unmeasured(e, "no usable recording");
        return e;
    }
    std::vector<double> raw(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
        raw[k] = samples[k].t_s;
    }
    e.sample_rate_hz = fit::median_rate(raw);
    if (e.sample_rate_hz < kMinSampleRateHz) {
        const std::string why = "the accelerometer read at " + text(e.sample_rate_hz) +
                                " Hz; timing the actuator needs 400 Hz or more (below, its "
                                "vibration aliases)";
        e.problems.push_back(why +
                             ": set the accelerometer's sampling frequency to 400 Hz or "
                             "more and calibrate again");
        set_unmeasured(e, why);
        return e;
    }
    const double covered = raw.back() - raw.front();
    if (raw.front() > first_drive_s(plan) || covered < 0.9 * (plan.duration_s() - raw.front())) {
        e.problems.push_back("the recording covers " + text(raw.front()) + "-" + text(raw.back()) +
                             " s but the probe plays 0-" + text(plan.duration_s()) +
                             " s: start recording before the probe and stop after it");
    }
    std::string which;
    if (clipped(samples, which)) {
        e.problems.push_back("the accelerometer clipped (" + which +
                             "): set its range wider (e.g. ±4 g), or hold the phone so the "
                             "actuator shakes it less hard");
    }
    const std::vector<Vec3> vibration = fit::high_pass(samples, high_pass_half(e.sample_rate_hz));
    if (plan.kind == Kind::lra) {
        estimate_lra(e, plan, samples, vibration, raw, nominal);
    } else {
        estimate_erm(e, plan, vibration,
                     fit::high_pass(samples, erm_energy_high_pass_half(e.sample_rate_hz)), raw);
    }
    if (e.snr_db < kMinSnrDb) {
        e.problems.push_back("no vibration felt: the actuator stands only " + text(e.snr_db, 2) +
                             " dB above the accelerometer's noise (" + text(kMinSnrDb, 2) +
                             " needed); lay the phone on a hard surface, or check that the "
                             "actuator runs and the accelerometer is the phone's own");
        e.spin_up_s.reset();
        e.spin_down_s.reset();
        e.resonance_hz.reset();
        e.q.reset();
        e.full_scale_accel.reset();
        set_unmeasured(e, "no vibration stood out of the noise");
    } else {
        const double limit = plan.kind == Kind::lra ? kMaxLraResidual : kMaxErmResidual;
        if (e.residual > limit) {
            e.problems.push_back("the model fits the recording poorly (residual " +
                                 text(e.residual, 2) + ", at most " + text(limit, 2) +
                                 " trusted): hold the phone still on a hard surface, away from "
                                 "other vibration, and calibrate again");
        }
    }
    if (e.snr_db >= kMinSnrDb) {
        judge_confidence(e);
    }
    e.trusted = e.problems.empty();
    return e;
}

void judge_confidence(Estimate& e) {
    if (e.kind == Kind::lra && e.resonance_hz && e.q && e.resonance_uncertainty &&
        e.q_uncertainty) {
        // Sampled at nearly twice the resonance, the ring and its mirror image about half the
        // rate fall within a fraction of the resonance's bandwidth of each other: the readings
        // then see their beat, slow against the decay, and the decay cannot be told from it
        // (bench/calibrate: Q off by 12-16 % through a sensor low-pass, every one of them
        // within 0.12 bandwidths; the resonance itself stays within 1 %).
        const double bandwidth = *e.resonance_hz / *e.q;
        const double apart = std::abs(e.sample_rate_hz - 2.0 * *e.resonance_hz) / bandwidth;
        if (apart < kMinMirrorBandwidths) {
            e.problems.push_back(
                "the resonance (" + text(*e.resonance_hz, 4) +
                " Hz) lies at half the accelerometer's sampling rate (" +
                text(e.sample_rate_hz, 4) +
                " Hz), where its ring cannot be told from its mirror image and the quality "
                "factor is not measurable: set the accelerometer's sampling frequency to another "
                "value (1 kHz is best) and calibrate again");
        } else if (e.mirror_hz && *e.resonance_uncertainty > kMaxResonanceUncertainty) {
            e.problems.push_back(
                "the resonance may be " + text(*e.resonance_hz, 4) + " Hz or its mirror image " +
                text(*e.mirror_hz, 4) + " Hz about half the accelerometer's sampling rate (" +
                text(e.sample_rate_hz, 4) + " Hz), which the recording cannot tell apart (±" +
                text(200.0 * *e.resonance_uncertainty, 2) + " %, at most ±" +
                text(200.0 * kMaxResonanceUncertainty, 2) +
                " % trusted): set the accelerometer's sampling frequency to another value (1 kHz "
                "is best) and calibrate again");
        } else if (*e.q_uncertainty > kMaxQUncertainty ||
                   *e.resonance_uncertainty > kMaxResonanceUncertainty) {
            e.problems.push_back("the probe's tones disagree: the resonance by ±" +
                                 text(200.0 * *e.resonance_uncertainty, 2) + " %, Q by ±" +
                                 text(200.0 * *e.q_uncertainty, 2) + " % (at most ±" +
                                 text(200.0 * kMaxResonanceUncertainty, 2) + " % and ±" +
                                 text(200.0 * kMaxQUncertainty, 2) +
                                 " % trusted); hold the phone still on a hard surface, read "
                                 "the accelerometer faster (1 kHz) and calibrate again");
        }
    }
    if (e.kind == Kind::erm && e.spin_up_uncertainty && e.spin_down_uncertainty) {
        const double doubt = std::max(*e.spin_up_uncertainty, *e.spin_down_uncertainty);
        if (doubt > kMaxSpinUncertainty) {
            e.problems.push_back(
                "the time constants are uncertain by ±" + text(200.0 * doubt, 2) + " % (at most ±" +
                text(200.0 * kMaxSpinUncertainty, 2) + " % trusted): " +
                (e.low_pass_doubt
                     ? "the accelerometer's own low-pass hides how fast the motor turns (read "
                       "at 1 kHz, or set the device's filter_low_pass_3db_frequency above the "
                       "motor's rotation) and calibrate again"
                     : "the probe's steps disagree; hold the phone still on a hard "
                       "surface, read the accelerometer faster (1 kHz) and calibrate again"));
        }
    }
    e.trusted = e.problems.empty();
}

Trace measured_magnitude(const std::vector<Sample>& samples, Kind kind) {
    Trace trace;
    if (samples.size() < 3) {
        return trace;
    }
    std::vector<double> raw(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
        raw[k] = samples[k].t_s;
    }
    const double rate = std::max(1.0, fit::median_rate(raw));
    const std::vector<Vec3> vibration = fit::high_pass(
        samples, kind == Kind::erm ? erm_energy_high_pass_half(rate) : high_pass_half(rate));
    std::vector<double> energy(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
        energy[k] = vibration[k][0] * vibration[k][0] + vibration[k][1] * vibration[k][1] +
                    vibration[k][2] * vibration[k][2];
    }
    energy = fit::box_smooth(energy, std::max(1, static_cast<int>(std::lround(0.005 * rate))));
    trace.t_s = raw;
    for (const double value : energy) {
        trace.magnitude.push_back(std::sqrt(2.0 * std::max(0.0, value)));
    }
    return trace;
}

Trace predicted_magnitude(const Plan& plan, const Declaration& constants, double full_scale_accel,
                          const std::vector<double>& t_s) {
    Declaration d = constants;
    d.kind = plan.kind;
    const Physics physics(d);
    Trace trace;
    trace.t_s = t_s;
    for (const double t : t_s) {
        State state;
        for (std::size_t i = 0; i < plan.rows.size(); ++i) {
            const double start = plan.rows[i].t_s;
            if (t <= start) {
                break;
            }
            const double end = i + 1 < plan.rows.size() ? plan.rows[i + 1].t_s : INFINITY;
            state = physics.advance(state, {plan.rows[i].amplitude, plan.rows[i].frequency_hz},
                                    std::min(t, end) - start);
        }
        // Strength 1 is what rated drive gives; full scale is 1 / rated of it (an ERM's speed),
        // and an ERM shakes with its speed squared.
        const double relative = Physics::strength(state) * d.rated_drive;
        trace.magnitude.push_back(full_scale_accel *
                                  (plan.kind == Kind::erm ? relative * relative : relative));
    }
    return trace;
}

Declaration apply(const Declaration& declared, const Estimate& estimate) {
    if (estimate.kind != declared.kind) {
        throw std::invalid_argument(std::string("calibration: the estimate is of an ") +
                                    (estimate.kind == Kind::erm ? "erm" : "lra") +
                                    " but the actuator is declared an " +
                                    (declared.kind == Kind::erm ? "erm" : "lra"));
    }
    if (!estimate.trusted) {
        std::string why = "calibration: the estimate is not trusted";
        if (!estimate.problems.empty()) {
            why += ": " + estimate.problems.front();
        }
        throw std::invalid_argument(why);
    }
    Declaration out = declared;
    if (declared.kind == Kind::erm) {
        out.spin_up_s = estimate.spin_up_s.value();
        out.spin_down_s = estimate.spin_down_s.value();
    } else {
        out.resonance_hz = estimate.resonance_hz.value();
        out.q = estimate.q.value();
    }
    return out;
}

Declaration with_measured_margins(Declaration declared) {
    if (declared.kind == Kind::lra) {
        declared.resonance_tolerance =
            std::min(declared.resonance_tolerance, kMeasuredResonanceTolerance);
        declared.q_tolerance = std::min(declared.q_tolerance, kMeasuredQTolerance);
    }
    return declared;
}

Declaration apply_as_daemon(const Declaration& declared, const Estimate& estimate) {
    return with_measured_margins(apply(declared, estimate));
}

std::string declaration_lines(const Estimate& estimate) {
    std::string out;
    if (estimate.spin_up_s) {
        out += std::string(kSpinUpMs.key) + " = " + text(*estimate.spin_up_s * 1000.0) + "\n";
    }
    if (estimate.spin_down_s) {
        out += std::string(kSpinDownMs.key) + " = " + text(*estimate.spin_down_s * 1000.0) + "\n";
    }
    if (estimate.resonance_hz) {
        out += std::string(kResonanceHz.key) + " = " + text(*estimate.resonance_hz, 4) + "\n";
    }
    if (estimate.q) {
        out += std::string(kQ.key) + " = " + text(*estimate.q) + "\n";
    }
    if (estimate.full_scale_accel) {
        out += "# strength: full scale shakes the phone with " + text(*estimate.full_scale_accel) +
               " m/s² peak" + (estimate.kind == Kind::lra ? " at resonance" : "") + "\n";
    }
    // Twice the standard error: the ± a person reads as "within".
    std::string doubt;
    const auto add_doubt = [&](const std::optional<double>& value, std::string_view key) {
        if (value) {
            doubt += std::string(doubt.empty() ? "" : ", ") + std::string(key) + " ±" +
                     text(200.0 * *value, 2) + " %";
        }
    };
    add_doubt(estimate.spin_up_uncertainty, kSpinUpMs.key);
    add_doubt(estimate.spin_down_uncertainty, kSpinDownMs.key);
    add_doubt(estimate.resonance_uncertainty, kResonanceHz.key);
    add_doubt(estimate.q_uncertainty, kQ.key);
    if (!doubt.empty()) {
        out += "# uncertainty: " + doubt + "\n";
    }
    out += "# fit: residual " + text(estimate.residual, 2) + ", signal-to-noise " +
           text(estimate.snr_db, 3) + " dB, sampled at " + text(estimate.sample_rate_hz, 4) +
           " Hz" + (estimate.trusted ? "" : ", not trusted") + "\n";
    for (const std::string& problem : estimate.problems) {
        out += "# problem: " + problem + "\n";
    }
    for (const std::string& missing : estimate.unmeasured) {
        out += "# not measured: " + missing + "\n";
    }
    return out;
}

}  // namespace vibscore::actuator::calibration
