#pragma once

namespace vibscore::drivers {

enum class ActuatorKind { erm, lra };

// The physical constants of a simulated actuator. Times are in seconds, frequencies in hertz.
struct ModelSettings {
    ActuatorKind kind = ActuatorKind::lra;
    // ERM: the motor speeds up faster under drive than it coasts down under friction.
    double spin_up_s = 0.050;
    double spin_down_s = 0.080;
    // LRA: a spring-mass resonator.
    double resonance_hz = 175.0;
    double q = 8.0;
};

// The vibration strength an actuator delivers over time in response to commands, 0 = still and
// 1 = full drive at its best frequency. Pure: time is whatever the caller passes, so it can be
// tested without clocks and evaluated at any instant.
//
// Between two commands the strength approaches its target exponentially, so response_at() is
// exact (analytic) rather than stepped. Times passed to command() must not decrease; an earlier
// time is treated as the time of the last command.
class ActuatorModel {
  public:
    // Throws std::invalid_argument naming a constant that is not a positive finite number.
    explicit ActuatorModel(const ModelSettings& settings = {});

    const ModelSettings& settings() const { return settings_; }

    // From t_s on, drive with amplitude (0..1) at frequency_hz (0: resonance, or ignored for an
    // ERM). Throws std::invalid_argument for a non-finite time, an amplitude outside 0..1 or a
    // negative or non-finite frequency.
    void command(double t_s, double amplitude, double frequency_hz);

    // The strength at t_s: 0 before the first command, and the strength at the last command for
    // times before it (only the latest segment is kept).
    double response_at(double t_s) const;

    // The strength the last command settles to: amplitude × steady_gain(frequency).
    double target() const { return target_; }

    // The time constant of the current approach to target().
    double time_constant_s() const { return tau_s_; }

    // The fraction of the commanded amplitude reached in the steady state at this frequency:
    // 1 for an ERM, lra_gain() for an LRA (frequency 0 = resonance).
    double steady_gain(double frequency_hz) const;

    // The resonator's amplitude response normalised to 1 at f0:
    //   G(f) = (1/Q) / sqrt((1 - (f/f0)²)² + (f/(Q f0))²)
    // With finite Q its true peak lies just below f0 and exceeds 1 slightly (by 0.2% at Q = 8).
    static double lra_gain(double frequency_hz, double resonance_hz, double q);

    // The LRA's envelope time constant Q/(π f0): the time its ringing takes to decay by 1/e.
    static double lra_time_constant_s(double resonance_hz, double q);

  private:
    ModelSettings settings_;
    bool commanded_ = false;  // before the first command the actuator is still
    double t0_s_ = 0.0;       // time of the last command
    double start_ = 0.0;      // strength at t0_s_
    double target_ = 0.0;
    double tau_s_ = 1.0;
};

}  // namespace vibscore::drivers
