#pragma once

#include "actuator/physics.hpp"

namespace vibscore::actuator {

// The strength a declared actuator delivers over time in response to drives, 0 = still and 1 =
// rated drive at its best frequency. Pure: time is whatever the caller passes, so it can be
// tested without clocks and evaluated at any instant, exactly (Physics is closed-form).
// Times passed to command() must not decrease; an earlier time counts as the last command's.
class Timeline {
  public:
    // Throws std::invalid_argument for impossible constants (Physics).
    explicit Timeline(const Declaration& declaration) : physics_(declaration) {}

    const Physics& physics() const { return physics_; }

    // From t_s on, drive with this amplitude (-1..1; negative = reverse or anti-phase) at this
    // frequency (0: the actuator's own). Throws std::invalid_argument for a non-finite time, an
    // amplitude outside -1..1 or a negative or non-finite frequency.
    void command(double t_s, const Drive& drive);

    // The state and strength at t_s: at rest before the first command, and the state at the last
    // command for times before it (only the latest segment is kept).
    State state_at(double t_s) const;
    double response_at(double t_s) const { return Physics::strength(state_at(t_s)); }

    // The drive in force since the last command, and the strength it settles to.
    const Drive& drive() const { return drive_; }
    double target() const { return physics_.steady_strength(drive_); }

  private:
    Physics physics_;
    bool commanded_ = false;
    double t0_s_ = 0.0;
    State state0_;
    Drive drive_;
};

}  // namespace vibscore::actuator
