#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"

// Measuring the actuator with the device's accelerometer (issue 32): the probe vibscore plays,
// what a recording of it says about the actuator, and how sure that is. Pure: no clock, no
// kernel, no bus. The daemon plays a plan and records it live (`vibscore calibrate`); any other
// recorder can do the same offline (`vibscore calibrate --plan` / `--estimate`); both end in
// estimate().
namespace vibscore::actuator::calibration {

// One row of a probe: from `t_s` on (seconds from the plan's start), drive with `amplitude`
// (-1..1 of full scale; negative = reverse or anti-phase) at `frequency_hz` (0: the actuator's
// own). The last row is the end: amplitude 0, and its time is the plan's length.
struct PlanRow {
    double t_s = 0.0;
    double amplitude = 0.0;
    double frequency_hz = 0.0;
};

struct Plan {
    Kind kind = Kind::lra;
    std::vector<PlanRow> rows;  // time order; the first at 0, the last an amplitude-0 end
    double duration_s() const { return rows.empty() ? 0.0 : rows.back().t_s; }
};

// The whole probe stays within these: short and quiet (docs/drivers.md, "Calibrating"). At most
// 3 s of vibration in all, within 6 s with the coasts and ring-downs between.
inline constexpr double kMaxVibrationSeconds = 3.0;
inline constexpr double kMaxPlanSeconds = 6.0;

// The probe for this kind. `nominal` (a declaration, possibly far from the truth) may centre an
// LRA's tones; without it the search covers every resonance the limits allow a phone LRA.
// Never above full scale; no longer than kMaxPlanSeconds, driven for kMaxVibrationSeconds at most.
Plan make_plan(Kind kind, const std::optional<Declaration>& nominal);

// The resonances an LRA probe covers: its lowest and highest tone, which are also the bounds of
// the search (an estimate at either edge is not trusted: the truth may lie beyond it).
struct LraRange {
    double low_hz = 0.0;
    double high_hz = 0.0;
};
LraRange lra_range(const std::optional<Declaration>& nominal);

// Below this rate an accelerometer aliases the vibration too much to time it: an estimate from a
// slower recording measures nothing and says so (`unmeasured`). A few per cent below 400 Hz
// still counts: sensors' clocks are not exact.
inline constexpr double kMinSampleRateHz = 388.0;

// A plan as the sim trace writes drives: the header `time_ns,amplitude,frequency_hz`, one row a
// line. parse_plan_csv reads it back; a malformed line is a std::invalid_argument naming
// `file:line` and the value.
std::string plan_csv(const Plan& plan);
Plan parse_plan_csv(const std::string& text, const std::string& file, Kind kind);

// One accelerometer reading: seconds from the plan's first row, and the three axes in m/s²
// (gravity included, axes in any orientation).
struct Sample {
    double t_s = 0.0;
    double x = 0.0, y = 0.0, z = 0.0;
};

// `t,x,y,z` rows (a header line is allowed); a malformed line is a std::invalid_argument naming
// `file:line` and the value.
std::vector<Sample> parse_samples_csv(const std::string& text, const std::string& file);

// What a recording says. Every number is set only where it could be measured; `unmeasured`
// says in words what could not be and why (sampling too slow for the resonance, ...).
struct Estimate {
    Kind kind = Kind::lra;
    std::optional<double> spin_up_s, spin_down_s;  // ERM
    std::optional<double> resonance_hz, q;         // LRA
    // The vibration at full-scale drive (at resonance for an LRA; full speed for an ERM), m/s²
    // peak: the strength scale.
    std::optional<double> full_scale_accel;
    double sample_rate_hz = 0.0;  // median rate of the recording
    double residual = 1.0;        // RMS misfit of the fitted model over RMS of the vibration, 0..
    double snr_db = 0.0;          // vibration over what is left when none is driven
    // How sure each number is, from the recording itself: a relative standard error (0.05:
    // about ±5 %), set with the number. An ERM's from how far the probe's steps disagree,
    // an LRA's from how far its ring-downs do. An estimate is trusted only while twice these
    // stay within what compensation is planned for (kMaxSpinUncertainty, ...).
    std::optional<double> spin_up_uncertainty, spin_down_uncertainty;
    std::optional<double> resonance_uncertainty, q_uncertainty;
    // An ERM's doubt is mostly what its answer leans on the sensor's own low-pass (fitted as a
    // first-order gain on the motor's speed), not what sets the probe's steps apart.
    bool low_pass_doubt = false;
    // An LRA sampled slower than twice its resonance: the mirror image about half the rate
    // (rate - resonance) that the recording cannot rule out, its distance then part of the
    // resonance's uncertainty.
    std::optional<double> mirror_hz;
    bool trusted = false;                 // every number set and the fit good enough to use
    std::vector<std::string> problems;    // why not trusted: each a sentence a person can act on
    std::vector<std::string> unmeasured;  // keys not measured, each with its reason
};

// How uncertain a number may be and still be trusted (a relative standard error, so twice it
// is the ±error allowed): issue 32's accuracy, ERM time constants ±15 %, LRA resonance ±1 % and
// Q ±15 %, which are also the margins compensation plans a measured LRA with (docs/drivers.md).
inline constexpr double kMaxSpinUncertainty = 0.075;
inline constexpr double kMaxResonanceUncertainty = 0.005;
inline constexpr double kMaxQUncertainty = 0.075;
// LRA: how far (in the resonance's bandwidths, f0 / Q) its mirror image about half the sampling
// rate must lie for its decay to be told from their beat.
inline constexpr double kMinMirrorBandwidths = 0.15;

// The trust rule on an estimate's uncertainties: adds a problem (what was uncertain, why, what
// to do) for each beyond its limit above, and sets `trusted` to whether there are none. An
// uncertainty exactly at its limit is still trusted. estimate() applies it; exposed so the rule
// is tested at its edges.
void judge_confidence(Estimate& e);

// Estimates the actuator's numbers from a recording of `plan`. `nominal` is what is declared
// (or nothing); it may guide the search but the result must not depend on it being right.
Estimate estimate(const Plan& plan, const std::vector<Sample>& samples,
                  const std::optional<Declaration>& nominal);

// For pictures and checks: the vibration's magnitude in a recording after the slowly varying
// part (gravity, the hand) is taken out as the estimate of that `kind` takes it out, smoothed
// over about a period; and the magnitude the model predicts at the same times for this plan
// under `constants` (the fitted numbers, or the declared ones), `full_scale_accel` m/s² peak at
// full-scale drive.
struct Trace {
    std::vector<double> t_s;
    std::vector<double> magnitude;
};
Trace measured_magnitude(const std::vector<Sample>& samples, Kind kind);
Trace predicted_magnitude(const Plan& plan, const Declaration& constants, double full_scale_accel,
                          const std::vector<double>& t_s);

// `declared` with the measured numbers of a trusted estimate in place of its own (the rest kept).
// Throws std::invalid_argument when the estimate is not trusted or is of another kind.
Declaration apply(const Declaration& declared, const Estimate& estimate);

// The margins compensation plans a measured LRA with: as well as a trusted estimate knows its
// numbers (twice the largest uncertainty trusted: resonance ±1 %, Q ±15 %), not a datasheet's
// part-to-part spread.
inline constexpr double kMeasuredResonanceTolerance = 2.0 * kMaxResonanceUncertainty;
inline constexpr double kMeasuredQTolerance = 2.0 * kMaxQUncertainty;

// An LRA whose resonance and Q were measured on this board: its tolerances no wider than the
// measured margins (a tolerance declared tighter stays), and with them the brake back
// (render::Uncertainty). An ERM has no tolerances and is returned as it is. The daemon's rule
// for numbers applied by `vibscore calibrate --apply` (daemon/calibration_state.cpp).
Declaration with_measured_margins(Declaration declared);

// What the daemon plays after `vibscore calibrate --apply`: apply(), then with_measured_margins().
// Throws as apply() does.
Declaration apply_as_daemon(const Declaration& declared, const Estimate& estimate);

// The `[actuator]` lines an estimate gives (`key = value`, one a line), the measured keys only,
// with the strength scale and the fit's quality as `#` comments.
std::string declaration_lines(const Estimate& estimate);

}  // namespace vibscore::actuator::calibration
