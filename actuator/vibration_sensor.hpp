#pragma once

#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "actuator/calibration.hpp"
#include "actuator/declaration.hpp"
#include "actuator/physics.hpp"

// What an accelerometer on the phone records while an actuator vibrates it: the calibration's
// benchmark and tests record plans with it, and the sim backend gives its simulated actuator an
// accelerometer with it. The actuator's TRUE constants may differ from what is declared.
//
// Physics (continuous time, integrated finely between readings):
//  LRA: the moving mass is a resonator, x'' + (w0/Q) x' + w0^2 x = F u cos(phase), the drive's
//       phase continuous across drive changes (as the backends drive it) and its frequency the
//       drive's (0: the true resonance). The phone feels the reaction to the mass's
//       acceleration x'' (or, with `lra_spring`, the spring's force), along one fixed axis.
//       F is such that full-scale drive at resonance
//       settles at `peak_accel`.
//  ERM: the motor's speed s (1 = the speed full-scale drive settles at) is first order, towards
//       the drive's amplitude with the spin-up time constant while driven and towards rest with
//       the spin-down one while not (as physics.hpp). The eccentric mass turns at
//       s x `erm_full_speed_hz` and shakes the phone with a centrifugal force that goes with s^2:
//       `peak_accel` s^2 cos(angle) along one axis (the phone's mounting lets it move one way:
//       the default), or, with `erm_rotating`, the force turning in a plane (both components).
// The sensor: its own uniform clock at `rate_hz` (or, with `jittered_sampling`, readings taken
// at jittered instants), timestamps reported with +-`jitter_s` uniform error, white noise of
// `noise_rms` per axis, gravity on a random axis, the vibration on a random axis, quantisation
// to `bits` over +-`range` (clipping there). Deterministic for a seed.
namespace vibscore::actuator {

struct SensorOptions {
    double rate_hz = 1000.0;
    double peak_accel = 10.0;  // m/s² peak at full-scale drive (at resonance / full speed)
    double erm_full_speed_hz = 180.0;
    bool erm_rotating = false;
    // LRA: the phone feels the mass's acceleration (false) or, mounted through its spring, the
    // spring's force, w0^2 x (true): the same ring, a resonance curve tilted the other way.
    bool lra_spring = false;
    double range = 4.0 * 9.80665;  // ±4 g
    int bits = 12;                 // 0: no quantisation
    double noise_rms = 0.02;       // m/s² per axis
    double gravity = 9.81;
    double jitter_s = 0.001;
    bool jittered_sampling = false;  // true: sampled at the jittered times, reported exactly
    double first_sample_s = 0.0;     // when the sensor's first reading is taken
    // The sensor's own anti-alias filter (many IMUs filter at ODR/2 or ODR/4): 0 none, else a
    // cascade of `low_pass_order` (1 or 2) first-order low-passes at `low_pass_hz` on the
    // vibration (gravity passes). It weakens and delays the vibration by its frequency.
    double low_pass_hz = 0.0;
    int low_pass_order = 1;
    std::uint64_t seed = 1;
};

class VibrationSensor {
  public:
    // Throws std::invalid_argument for a truth Physics refuses or a rate that is not positive.
    VibrationSensor(const Declaration& truth, const SensorOptions& options);

    // From `t_s` on the actuator is driven with `drive` (seconds on the sensor's time line;
    // a time already simulated takes effect at once).
    void command(double t_s, const Drive& drive);

    // The readings taken up to and including `t_s`, in order, each once.
    std::vector<calibration::Sample> sample_until(double t_s);

    const SensorOptions& options() const { return options_; }

  private:
    struct Command {
        double t_s;
        Drive drive;
    };
    void advance_to(double t_s);
    void step(double h);
    double vibration() const;         // along the vibration axis (ERM: first component)
    double second_component() const;  // a rotating ERM's along the second axis
    void filter(double h);            // the sensor's low-pass over a step of h
    double next_sample_time();

    Declaration truth_;
    SensorOptions options_;
    std::mt19937_64 random_;
    std::deque<Command> pending_;
    Drive drive_{};
    double t_ = 0.0;
    // LRA: position, velocity, drive phase; ERM: speed, angle.
    double x_ = 0.0, v_ = 0.0, phase_ = 0.0;
    double speed_ = 0.0, angle_ = 0.0;
    double axis_[3]{}, axis2_[3]{}, gravity_[3]{};
    // The low-pass's stages, for the vibration along each axis.
    double filtered_a_[2]{}, filtered_b_[2]{};
    long index_ = 0;
    double due_ = 0.0;           // when the next reading is taken
    double due_reported_ = 0.0;  // the time it is reported at
};

// `plan` recorded from its start to its end plus `tail_s`, the actuator following it `delay_s`
// late (the drive path's latency).
std::vector<calibration::Sample> record(const calibration::Plan& plan, const Declaration& truth,
                                        const SensorOptions& options, double delay_s = 0.0,
                                        double tail_s = 0.0);

}  // namespace vibscore::actuator
