#pragma once

#include <array>
#include <functional>
#include <vector>

#include "actuator/calibration.hpp"

// The numerical parts of estimate() (internal to the actuator library): the recording's time
// line, its vibration with gravity and the hand taken out, and the two model fits.
namespace vibscore::actuator::calibration::fit {

using Vec3 = std::array<double, 3>;

// The median of the intervals between readings, as a rate (0 for fewer than two readings).
double median_rate(const std::vector<double>& t_s);

// The readings' times as the sensor's own clock most likely took them: a straight line through
// the reported times against the readings' order. Reported times jitter; a sensor's clock does
// not, so this removes the jitter when the readings were in fact uniform.
std::vector<double> regular_times(const std::vector<double>& t_s);

// A centred moving average over 2 `half` + 1 readings (fewer at the ends).
std::vector<double> box_smooth(const std::vector<double>& values, int half);

// Each axis minus its slowly varying part (a triangular moving average 4 `half` + 1 readings
// wide): gravity and the hand's movement out, the vibration left.
std::vector<Vec3> high_pass(const std::vector<Sample>& samples, int half);

// The direction the vibration mostly takes (principal axis of the readings), unit length.
Vec3 principal_axis(const std::vector<Vec3>& vibration);

// The spread of the vibration along its three principal axes, largest first (eigenvalues of
// its covariance).
Vec3 principal_spread(const std::vector<Vec3>& vibration);

// Minimises `f` from `start` (Nelder-Mead) with initial steps `step`; returns the best point.
std::vector<double> minimise(const std::function<double(const std::vector<double>&)>& f,
                             std::vector<double> start, const std::vector<double>& step,
                             int iterations);

// An LRA's ring: resonance (undamped, Hz) and amplitude decay rate (1/s), the plan's time offset
// in the recording, and what the fit leaves.
struct LraFit {
    double resonance_hz = 0.0;
    double decay_per_s = 0.0;
    double offset_s = 0.0;
    double rss = 0.0;           // what the model leaves
    double vibration_ss = 0.0;  // what a model without vibration leaves (the vibration's energy)
    double samples = 0.0;
    double tone_misfit = 1.0;  // tones' steady strengths against the resonance curve, relative
    double full_scale = 0.0;   // steady peak acceleration at full-scale drive at resonance
    // The mirror about half the sampling rate that explains the readings as well (0: none),
    // its tones' misfit, and whether the answer is the middle of the two (a few hertz apart).
    double rival_hz = 0.0;
    double rival_misfit = 1.0;
    bool rival_middle = false;
};
// `t_s` and `signal` (the reading along the vibration's axis); the search spans `low_hz` ..
// `high_hz`; `rate_hz` is the sampling rate (for the alias of each candidate).
LraFit fit_lra(const Plan& plan, const std::vector<double>& t_s, const std::vector<double>& signal,
               double low_hz, double high_hz, double rate_hz);

// How far the probe's tones disagree: each tone with its ring-down fitted alone (the offset
// held, starting from `fit`), the spread of their log resonance and log Q as a standard error
// of their mean.
struct LraSpread {
    double resonance = 1.0;
    double q = 1.0;
    int pairs = 0;
};
LraSpread lra_pair_spread(const Plan& plan, const std::vector<double>& t_s,
                          const std::vector<double>& signal, const LraFit& fit);

// An ERM's speed: time constants, delay, and the energy fit.
struct ErmFit {
    double spin_up_s = 0.0;
    double spin_down_s = 0.0;
    double delay_s = 0.0;
    double scale = 0.0;  // smoothed |vibration|^2 at full speed
    double floor = 0.0;  // smoothed |vibration|^2 at rest (noise)
    double rss = 0.0;
    double energy_ss = 0.0;  // the energy's own spread about the floor
    double filter = 0.0;     // the sensor low-pass kept: full-speed rotation over its corner
    int filter_stages = 1;   // ... and its stages (first-order sections at that corner)
    // How much the constants lean on the low-pass model (log, a standard error): see fit_erm.
    double filter_doubt_up = 0.0;
    double filter_doubt_down = 0.0;
};
// What an ERM's trace is at each reading: |vibration|^2 smoothed by box_smooth over `half` (the
// mean of speed^4 there), or erm_envelope's (speed^4 at the reading).
enum class ErmTrace { averaged_energy, coherent_envelope };

// `energy`: the trace; `weight`: how much each reading's is to be believed (weighted least
// squares). A sensor low-pass on the vibration is tried (kept only where it clearly explains
// more).
ErmFit fit_erm(const Plan& plan, const std::vector<double>& t_s, const std::vector<double>& energy,
               const std::vector<double>& weight, int half,
               ErmTrace trace = ErmTrace::averaged_energy);

// How far the probe's steps disagree: each step (its rise and its coast) fitted alone, the
// delay and sensor low-pass of `fit` held, starting from `fit`'s constants; the standard error
// of the steps' mean log constant (0.05: about ±5 %). The steps are repeats of one experiment,
// so what sets them apart is what the recording does not determine: noise, the sampled phase,
// a beat of the rotation with the sampling, a low-pass the fit cannot tell from a slower motor.
struct ErmSpread {
    double spin_up = 1.0;
    double spin_down = 1.0;
    int bursts = 0;
};
ErmSpread erm_burst_spread(const Plan& plan, const std::vector<double>& t_s,
                           const std::vector<double>& energy, const std::vector<double>& weight,
                           int half, const ErmFit& fit, ErmTrace trace = ErmTrace::averaged_energy);

// An ERM's vibration envelope independent of the phase at which the readings fall (for readings
// at jittered instants, where |vibration|^2 carries the sampled phase as noise): the rotation
// frequency at full speed from the plateaus' spectrum, the phase the speed model `first`
// predicts from it, and in a window of 2 `half` + 1 readings around each one the sinusoid at
// that phase, carrying the force that model predicts (speed^2), fitted per axis: how much
// stronger the vibration is than the model there, times the model's force at the reading
// (amplitude^2 summed over the axes, so it goes with speed^4 as the energy does). `weight` is how
// well each window's phases separate the sine from the cosine (near 0 where the sampling aliases
// the rotation to zero or half the rate, or the motor is nearly still). `explained` is the share of
// the vibration the local sinusoids explain: the readings' right time base explains more.
// `high_pass_half`: the vibration went through high_pass with it (the sinusoids then do too, so
// what it takes away is not read as a weaker vibration); 0: it did not.
struct ErmEnvelope {
    std::vector<double> envelope;
    std::vector<double> weight;
    double full_speed_hz = 0.0;
    double explained = 0.0;
};
ErmEnvelope erm_envelope(const Plan& plan, const std::vector<double>& t_s,
                         const std::vector<Vec3>& vibration, const ErmFit& first, int half,
                         int high_pass_half);

// An ERM's normalised speed (1 = full scale's) at each of `t_s` under `plan`, shifted `delay_s`.
std::vector<double> erm_speeds(const Plan& plan, double spin_up_s, double spin_down_s,
                               double delay_s, const std::vector<double>& t_s);

}  // namespace vibscore::actuator::calibration::fit
