#pragma once

#include <complex>
#include <optional>
#include <vector>

#include "actuator/declaration.hpp"

namespace vibscore::actuator {

// One drive as a backend sends it: amplitude -1..1 of full scale, a negative one driving in
// reverse (an ERM) or in anti-phase (an LRA); frequency 0 is the actuator's own (an LRA's
// resonance; an ERM has no other).
struct Drive {
    double amplitude = 0.0;
    double frequency_hz = 0.0;
    bool operator==(const Drive&) const = default;
};

// What the actuator is doing at one instant, in strength units (1 = what rated drive gives in the
// steady state, at resonance for an LRA).
//  ERM: `envelope` is real, the motor's speed; negative when it spins backwards.
//  LRA: `envelope` is the complex amplitude of its vibration relative to the phase of the drive
//       (a frame turning at `frame_hz`): real and positive when it moves in phase with a forward
//       drive, negative in anti-phase. Between drives the frame keeps turning at the last drive's
//       frequency, so a drive that starts again continues that phase.
// The strength a person feels is |envelope|.
struct State {
    std::complex<double> envelope{};
    double frame_hz = 0.0;
};

// How a declared actuator responds to its drive: pure, exact and closed-form between drives.
//
// ERM: a DC motor's speed is first order. While driven (any non-zero amplitude, either way) it
// follows the drive with the spin-up time constant towards amplitude / rated-drive (so driven
// backwards it slows through zero towards the reverse speed); undriven it coasts towards rest
// with the spin-down time constant.
//
// LRA: a resonator at f0 with quality Q, as its slowly varying envelope z in the frame of the
// drive at f:  dz/dt = -(1/tau + i 2 pi (f - f0)) z + k(f) u / tau,  tau = Q / (pi f0).
// The envelope builds up and rings down with tau; driven off resonance it beats at |f - f0| on
// the way; anti-phase drive (u < 0) pushes it down. k(f) makes the steady strength exactly
// u / rated-drive x G(f), the resonator's amplitude response normalised to 1 at f0:
//   G(f) = (1/Q) / sqrt((1 - (f/f0)^2)^2 + (f / (Q f0))^2).
class Physics {
  public:
    // Throws std::invalid_argument naming a constant that is not a positive finite number.
    explicit Physics(const Declaration& declaration);

    const Declaration& declaration() const { return declaration_; }
    bool is_lra() const { return declaration_.kind == Kind::lra; }

    static double strength(const State& state) { return std::abs(state.envelope); }

    // The frequency a drive vibrates at: its own, or the resonance for 0 (an ERM: 0).
    double frequency_of(const Drive& drive) const;
    // The steady strength at this frequency relative to resonance: 1 for an ERM, G(f) for an LRA
    // (frequency 0: the resonance).
    double gain(double frequency_hz) const;
    // The strength a drive settles to: |amplitude| / rated-drive x gain.
    double steady_strength(const Drive& drive) const;
    // The amplitude that settles to `strength` at this frequency (unclamped: above 1 it is out of
    // reach of the backend).
    double amplitude_for(double strength, double frequency_hz) const;
    // The time constant the strength moves with under this drive.
    double time_constant_s(const Drive& drive) const;

    // The state `dt_s` seconds on, under `drive` throughout.
    State advance(const State& state, const Drive& drive, double dt_s) const;

    // How long, under `drive` from `state`, the strength takes to reach `level` (from below or
    // above, whichever side it starts on), looking no further than `horizon_s`:
    //  reached  - it gets there after `after_s`;
    //  stalled  - it turns back (or stops) before getting there, after `after_s` (an LRA beating
    //             off resonance; an ERM settling short of the level): driving on would not help
    //             (a dip first, where what rings meets a push against it, is not turning back);
    //  horizon  - still on its way at `horizon_s`.
    struct Reach {
        enum class Outcome { reached, stalled, horizon };
        Outcome outcome;
        double after_s;
    };
    Reach time_to(const State& state, const Drive& drive, double level, double horizon_s) const;

    // An LRA braked to rest: driven off resonance it moves out of phase with its drive, so
    // anti-phase at the drive's own frequency leaves the quadrature part of its motion ringing.
    // This finds the frequencies of an anti-phase drive of `amplitude` (0..1 of full scale; its
    // phase continuing the last drive's, as the backends do) under which the envelope passes
    // exactly through zero, and when: every one within `search_hz` of the resonance, the quickest
    // first. None for an ERM, or when none does.
    struct RestBrake {
        double frequency_hz;
        double after_s;
    };
    std::vector<RestBrake> brakes_to_rest(const State& state, double search_hz,
                                          double amplitude = 1.0) const;

    // The resonator's amplitude response normalised to 1 at f0 (above).
    static double lra_gain(double frequency_hz, double resonance_hz, double q);
    // lra_gain solved backwards: the frequencies where it is at least `gain` (> 0), from
    // low_hz (0 when it reaches down to DC) to high_hz; nothing when no frequency gives that much.
    struct GainBand {
        double low_hz;
        double high_hz;
    };
    static std::optional<GainBand> lra_band(double gain, double resonance_hz, double q);

  private:
    // The envelope's rate -(1/tau + i delta) and its steady value under a drive.
    struct Motion {
        std::complex<double> rate;
        std::complex<double> steady;
    };
    Motion motion(const State& state, const Drive& drive) const;
    Reach time_to_numeric(const State& state, const Drive& drive, double level,
                          double horizon_s) const;

    Declaration declaration_;
    double lra_tau_s_ = 1.0;
};

}  // namespace vibscore::actuator
