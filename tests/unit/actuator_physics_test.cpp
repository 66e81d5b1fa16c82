// The declared actuator's physics (actuator/) against closed forms: an ERM's first-order
// speed under forward drive, coasting and reverse drive; an LRA's envelope building up, ringing
// down and pushed down by anti-phase drive, weaker and beating off resonance.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "actuator/physics.hpp"
#include "actuator/timeline.hpp"

namespace vibscore::actuator {
namespace {

using Outcome = Physics::Reach::Outcome;
constexpr double kE = std::numbers::e;

Declaration erm() {
    Declaration declaration;
    declaration.kind = Kind::erm;
    declaration.rated_drive = 0.7;
    declaration.spin_up_s = 0.040;
    declaration.spin_down_s = 0.080;
    return declaration;
}

Declaration lra(double q = 15.0, double f0 = 175.0) {
    Declaration declaration;
    declaration.kind = Kind::lra;
    declaration.rated_drive = 0.7;
    declaration.resonance_hz = f0;
    declaration.q = q;
    return declaration;
}

State at_rest() {
    return {};
}

State steady(const Physics& physics, const Drive& drive) {
    return physics.advance(at_rest(), drive, 100.0);
}

TEST(ActuatorPhysics, AnErmSpinsUpToRatedStrengthWithItsSpinUpConstant) {
    const Physics physics(erm());
    const State after = physics.advance(at_rest(), {0.7, 0.0}, 0.040);
    EXPECT_NEAR(Physics::strength(after), 1.0 - 1.0 / kE, 1e-12);
    EXPECT_NEAR(Physics::strength(steady(physics, {0.7, 0.0})), 1.0, 1e-12);
}

TEST(ActuatorPhysics, FullScaleDrivesAnErmBeyondRatedStrength) {
    const Physics physics(erm());
    EXPECT_NEAR(physics.steady_strength({1.0, 0.0}), 1.0 / 0.7, 1e-12);
    EXPECT_NEAR(Physics::strength(physics.advance(at_rest(), {1.0, 0.0}, 0.040)),
                (1.0 / 0.7) * (1.0 - 1.0 / kE), 1e-12);
}

TEST(ActuatorPhysics, AnUndrivenErmCoastsWithItsSpinDownConstant) {
    const Physics physics(erm());
    const State spinning = steady(physics, {0.7, 0.0});
    EXPECT_NEAR(Physics::strength(physics.advance(spinning, {0.0, 0.0}, 0.080)), 1.0 / kE, 1e-12);
}

TEST(ActuatorPhysics, AnErmDrivenLowerFollowsItsDriveWithTheSpinUpConstant) {
    const Physics physics(erm());
    const State spinning = steady(physics, {0.7, 0.0});
    // From 1 towards 0.5: the driver holds its voltage, and back-EMF above it brakes.
    const State after = physics.advance(spinning, {0.35, 0.0}, 0.040);
    EXPECT_NEAR(Physics::strength(after), 0.5 + 0.5 / kE, 1e-12);
}

TEST(ActuatorPhysics, AnErmDrivenBackwardsFallsThroughZeroTowardsTheReverseSpeed) {
    const Physics physics(erm());
    const State spinning = steady(physics, {0.7, 0.0});
    const double reverse = 1.0 / 0.7;
    // z(t) = -U + (1 + U) e^(-t / spin-up)
    const double zero_at = 0.040 * std::log((1.0 + reverse) / reverse);
    EXPECT_NEAR(physics.advance(spinning, {-1.0, 0.0}, zero_at).envelope.real(), 0.0, 1e-12);
    const State later = physics.advance(spinning, {-1.0, 0.0}, 0.2);
    EXPECT_LT(later.envelope.real(), 0.0);  // spinning backwards
    EXPECT_NEAR(Physics::strength(later), reverse - (1.0 + reverse) * std::exp(-0.2 / 0.040),
                1e-12);
    EXPECT_EQ(physics.time_constant_s({-1.0, 0.0}), 0.040);
}

TEST(ActuatorPhysics, AnErmIgnoresFrequency) {
    const Physics physics(erm());
    EXPECT_EQ(physics.gain(50.0), 1.0);
    EXPECT_EQ(Physics::strength(physics.advance(at_rest(), {0.5, 300.0}, 0.03)),
              Physics::strength(physics.advance(at_rest(), {0.5, 0.0}, 0.03)));
}

TEST(ActuatorPhysics, AnLraBuildsUpAndRingsDownWithQOverPiF0) {
    const Physics physics(lra(10.0, 200.0));
    const double tau = 10.0 / (std::numbers::pi * 200.0);
    EXPECT_DOUBLE_EQ(physics.time_constant_s({1.0, 0.0}), tau);
    const State built = physics.advance(at_rest(), {0.7, 0.0}, tau);
    EXPECT_NEAR(Physics::strength(built), 1.0 - 1.0 / kE, 1e-12);
    const State full = steady(physics, {0.7, 200.0});
    EXPECT_NEAR(Physics::strength(physics.advance(full, {0.0, 0.0}, tau)), 1.0 / kE, 1e-12);
}

TEST(ActuatorPhysics, AntiPhaseDrivePushesAnLraDownThroughZero) {
    const Physics physics(lra());
    const double tau = lra_time_constant_s(175.0, 15.0);
    const State full = steady(physics, {0.7, 0.0});
    // z(t) = -1 + 2 e^(-t/tau) under rated anti-phase drive: zero after tau ln 2.
    const State stopped = physics.advance(full, {-0.7, 0.0}, tau * std::log(2.0));
    EXPECT_NEAR(Physics::strength(stopped), 0.0, 1e-12);
    const State beyond = physics.advance(full, {-0.7, 0.0}, 2.0 * tau);
    EXPECT_LT(beyond.envelope.real(), 0.0);  // now in anti-phase to the old drive
}

TEST(ActuatorPhysics, AnLraIsWeakerOffResonanceByItsGainCurve) {
    const Physics physics(lra());
    for (const double f : {150.0, 170.0, 175.0, 181.0, 235.0}) {
        const double g = Physics::lra_gain(f, 175.0, 15.0);
        EXPECT_NEAR(Physics::strength(steady(physics, {0.7, f})), g, 1e-9) << f;
        EXPECT_NEAR(physics.steady_strength({0.7, f}), g, 1e-12) << f;
        EXPECT_NEAR(physics.amplitude_for(g, f), 0.7, 1e-12) << f;
    }
    // The figure: full drive at 235 Hz gives 8 % of what it gives at 175 Hz.
    EXPECT_NEAR(Physics::lra_gain(235.0, 175.0, 15.0), 0.0825, 0.0005);
}

TEST(ActuatorPhysics, TheGainBandIsTheGainCurveSolvedBackwards) {
    for (const double gain : {0.1, 0.5, 0.9, 1.0}) {
        const auto band = Physics::lra_band(gain, 175.0, 15.0);
        ASSERT_TRUE(band) << gain;
        EXPECT_LT(band->low_hz, 175.0);
        EXPECT_GT(band->high_hz, 175.0);
        EXPECT_NEAR(Physics::lra_gain(band->low_hz, 175.0, 15.0), gain, 1e-9) << gain;
        EXPECT_NEAR(Physics::lra_gain(band->high_hz, 175.0, 15.0), gain, 1e-9) << gain;
    }
    // The curve peaks a little above 1 just below f0 (at Q 15: 1 / sqrt(1 - 1/(4 Q^2))).
    const double peak = 1.0 / std::sqrt(1.0 - 1.0 / (4.0 * 15.0 * 15.0));
    EXPECT_TRUE(Physics::lra_band(peak * (1.0 - 1e-9), 175.0, 15.0));
    EXPECT_FALSE(Physics::lra_band(peak * (1.0 + 1e-9), 175.0, 15.0));
    // A gain the curve keeps down to DC starts the band at 0 Hz (Q 1: G(0) = 1).
    EXPECT_EQ(Physics::lra_band(0.5, 175.0, 1.0)->low_hz, 0.0);
}

TEST(ActuatorPhysics, OffResonanceAnLraBuildsUpBeatingAtTheDetuning) {
    const Physics physics(lra());
    const double f = 185.0;
    const double gamma = 1.0 / lra_time_constant_s(175.0, 15.0);
    const double delta = 2.0 * std::numbers::pi * (f - 175.0);
    const double settled = Physics::lra_gain(f, 175.0, 15.0) / 0.7;
    for (const double t : {0.002, 0.01, 0.03, 0.05, 0.1}) {
        // |z(t)| = |z_inf| |1 - e^-(gamma + i delta) t|
        const double expected =
            settled * std::sqrt(1.0 - 2.0 * std::exp(-gamma * t) * std::cos(delta * t) +
                                std::exp(-2.0 * gamma * t));
        EXPECT_NEAR(Physics::strength(physics.advance(at_rest(), {1.0, f}, t)), expected, 1e-12)
            << t;
    }
}

TEST(ActuatorPhysics, RingingAnLraTurnsAgainstAnOffTuneDrivesPhase) {
    const Physics physics(lra());
    const State driven = steady(physics, {0.7, 180.0});
    const State later = physics.advance(driven, {0.0, 0.0}, 0.01);
    EXPECT_EQ(later.frame_hz, 180.0);
    const double turned = std::arg(later.envelope / driven.envelope);
    EXPECT_NEAR(turned, std::remainder(-2.0 * std::numbers::pi * 5.0 * 0.01, 2 * std::numbers::pi),
                1e-9);
}

TEST(ActuatorPhysics, FrequencyZeroIsTheResonance) {
    const Physics physics(lra(15.0, 235.0));
    EXPECT_EQ(physics.gain(0.0), 1.0);
    EXPECT_EQ(physics.frequency_of({0.5, 0.0}), 235.0);
    EXPECT_NEAR(Physics::lra_gain(235.0, 235.0, 15.0), 1.0, 1e-15);
}

TEST(ActuatorPhysics, TimeToReachAStrengthIsTheClosedForm) {
    const Physics physics(erm());
    const double full = 1.0 / 0.7;
    auto reach = physics.time_to(at_rest(), {1.0, 0.0}, 0.9, 1.0);
    EXPECT_EQ(reach.outcome, Outcome::reached);
    EXPECT_NEAR(reach.after_s, 0.040 * std::log(full / (full - 0.9)), 1e-12);

    const State spinning = steady(physics, {0.7, 0.0});
    reach = physics.time_to(spinning, {-1.0, 0.0}, 0.0, 1.0);
    EXPECT_EQ(reach.outcome, Outcome::reached);
    EXPECT_NEAR(reach.after_s, 0.040 * std::log((1.0 + full) / full), 1e-12);

    // Coasting never quite reaches rest; out of reach beyond full scale; at once when there.
    EXPECT_EQ(physics.time_to(spinning, {0.0, 0.0}, 0.0, 1.0).outcome, Outcome::horizon);
    EXPECT_EQ(physics.time_to(at_rest(), {1.0, 0.0}, 1.5, 1.0).outcome, Outcome::horizon);
    EXPECT_EQ(physics.time_to(spinning, {0.7, 0.0}, 1.0, 1.0).after_s, 0.0);
    // Within the horizon only.
    EXPECT_EQ(physics.time_to(at_rest(), {1.0, 0.0}, 0.9, 0.01).outcome, Outcome::horizon);
    // A drive that moves away never gets there.
    EXPECT_EQ(physics.time_to(spinning, {0.0, 0.0}, 1.2, 1.0).outcome, Outcome::stalled);
}

TEST(ActuatorPhysics, TimeToReachOffResonanceFindsTheFirstCrossingOrThePeak) {
    const Physics physics(lra());
    const double f = 185.0;
    const double level = 0.3;
    const auto reach = physics.time_to(at_rest(), {1.0, f}, level, 1.0);
    ASSERT_EQ(reach.outcome, Outcome::reached);
    EXPECT_NEAR(Physics::strength(physics.advance(at_rest(), {1.0, f}, reach.after_s)), level,
                1e-9);
    for (double t = 0.0; t < reach.after_s - 1e-6; t += reach.after_s / 100.0) {
        EXPECT_LT(Physics::strength(physics.advance(at_rest(), {1.0, f}, t)), level);
    }
    // Far off tune the envelope peaks below the level and turns back: drive no longer.
    const auto peak = physics.time_to(at_rest(), {1.0, 235.0}, 0.5, 1.0);
    ASSERT_EQ(peak.outcome, Outcome::stalled);
    const double at_peak =
        Physics::strength(physics.advance(at_rest(), {1.0, 235.0}, peak.after_s));
    EXPECT_GT(at_peak,
              Physics::strength(physics.advance(at_rest(), {1.0, 235.0}, peak.after_s - 1e-4)));
    EXPECT_GT(at_peak,
              Physics::strength(physics.advance(at_rest(), {1.0, 235.0}, peak.after_s + 1e-4)));
}

TEST(ActuatorPhysics, APushMeetingWhatRingsAgainstItGoesThroughItsLeastAndOnToTheLevel) {
    // What a brake left (a hair of it, in anti-phase) is first taken down by a push off
    // resonance, and then up: the push gets there, it does not stall at once. A brake meeting
    // what rings in phase with it would first make it louder: that one does stall at once.
    const Physics physics(lra(8.0, 235.0));
    const Drive push{1.0, 248.0};
    const State residue{{-0.0008, 0.0001}, 248.0};
    const auto reach = physics.time_to(residue, push, 0.5, 1.0);
    ASSERT_EQ(reach.outcome, Outcome::reached);
    EXPECT_NEAR(Physics::strength(physics.advance(residue, push, reach.after_s)), 0.5, 1e-9);
    EXPECT_LT(Physics::strength(physics.advance(residue, push, 1e-5)), Physics::strength(residue));
    // Still in the dip at the horizon: on its way, not stalled.
    EXPECT_EQ(physics.time_to(residue, push, 0.5, 1e-5).outcome, Outcome::horizon);

    const State ringing{{-0.5, 0.05}, 248.0};
    const auto brake = physics.time_to(ringing, {-1.0, 248.0}, 0.2, 1.0);
    EXPECT_EQ(brake.outcome, Outcome::stalled);
    EXPECT_EQ(brake.after_s, 0.0);
}

TEST(ActuatorPhysics, RejectsImpossibleConstants) {
    for (auto spoil :
         {+[](Declaration& d) { d.q = 0.0; }, +[](Declaration& d) { d.spin_down_s = -1.0; },
          +[](Declaration& d) { d.rated_drive = 0.0; },
          +[](Declaration& d) { d.resonance_hz = NAN; }}) {
        Declaration declaration = lra();
        spoil(declaration);
        EXPECT_THROW(Physics{declaration}, std::invalid_argument);
    }
}

TEST(ActuatorTimeline, IsAtRestBeforeTheFirstCommandAndContinuousAcrossCommands) {
    Timeline model(erm());
    EXPECT_EQ(model.response_at(5.0), 0.0);
    model.command(1.0, {0.7, 0.0});
    const double at_switch = model.response_at(1.03);
    model.command(1.03, {0.0, 0.0});
    EXPECT_DOUBLE_EQ(model.response_at(1.03), at_switch);
    EXPECT_NEAR(model.response_at(1.03 + 0.080), at_switch / kE, 1e-12);
    EXPECT_EQ(model.target(), 0.0);
}

TEST(ActuatorTimeline, AnEarlierCommandTimeCountsAsTheLastOne) {
    Timeline model(erm());
    model.command(1.0, {0.7, 0.0});
    model.command(0.5, {0.0, 0.0});
    EXPECT_DOUBLE_EQ(model.response_at(1.0), 0.0);
    EXPECT_NEAR(model.response_at(1.080), 0.0, 1e-15);
}

TEST(ActuatorTimeline, TakesReverseDriveAndRejectsImpossibleCommands) {
    Timeline model(lra());
    model.command(0.0, {-1.0, 175.0});
    EXPECT_NEAR(model.target(), 1.0 / 0.7, 1e-12);
    EXPECT_THROW(model.command(0.0, {1.0000001, 0.0}), std::invalid_argument);
    EXPECT_THROW(model.command(0.0, {-1.0000001, 0.0}), std::invalid_argument);
    EXPECT_THROW(model.command(0.0, {NAN, 0.0}), std::invalid_argument);
    EXPECT_THROW(model.command(0.0, {0.5, -1.0}), std::invalid_argument);
    EXPECT_THROW(model.command(INFINITY, {0.5, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace vibscore::actuator
