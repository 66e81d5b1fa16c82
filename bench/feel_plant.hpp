#pragma once

#include <vector>

#include "actuator/declaration.hpp"
#include "daemon/render/cue_stream.hpp"

namespace vibscore::bench {

// The benchmark's own actuator, deliberately not the renderer's: its differential equations
// integrated numerically (fourth-order Runge-Kutta, a few dozen steps per period), so that
// compensation planned with actuator::Physics' closed forms is judged by a model it was not made
// with.
//  ERM: the motor's speed w, dw/dt = (u / rated - w) / spin-up while driven (either way), and
//       -w / spin-down while coasting; strength |w|.
//  LRA: a mass on a spring, x'' + (w0 / Q) x' + w0^2 x = F u cos(phase), the drive's phase
//       advancing at its frequency without a jump when it changes; strength is the amplitude of
//       x (from x and x' at the frequency it moves at), 1 at resonance under rated drive. Unlike
//       the renderer's envelope model it has both the drive's and its own frequency in it, and
//       every cycle.
class Plant {
  public:
    explicit Plant(const actuator::Declaration& truth);

    // The strength under `drives` (drive cues as the player sends them: amplitude -1..1 of full
    // scale, frequency 0 = resonance), sampled at `rate_hz` for `count` samples from time 0.
    std::vector<double> respond(const std::vector<render::Cue>& drives, double rate_hz,
                                std::size_t count) const;

  private:
    std::vector<double> respond_erm(const std::vector<render::Cue>& drives, double rate_hz,
                                    std::size_t count) const;
    std::vector<double> respond_lra(const std::vector<render::Cue>& drives, double rate_hz,
                                    std::size_t count) const;

    actuator::Declaration truth_;
};

}  // namespace vibscore::bench
