// The declared LRA's whole motion (actuator/resonator_motion.*), against bench/feel's plant (the
// same equation integrated step by step) and against the closed forms it must agree with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "actuator/physics.hpp"
#include "actuator/resonator_motion.hpp"
#include "bench/feel_plant.hpp"
#include "tests/support/example_actuators.hpp"

namespace vibscore::actuator {
namespace {

using vibscore::testing::example_erm;
using vibscore::testing::example_lra;

// `note` from rest, settled by `settled`, then `brake` watched around `quiet` to `length` in 64
// looks; the watch, and the largest rebound it said at its last look.
std::pair<ResonatorMotion::Brake, double> braked_after_settling(const Physics& physics,
                                                                const Drive& note, double settled,
                                                                const Drive& brake, double quiet,
                                                                double length) {
    ResonatorMotion motion;
    motion.change(physics, 0.0, {}, note);
    auto watch = motion.braking(physics, settled, note, brake, quiet);
    double rebound = 0.0;
    for (int k = 1; k <= 64; ++k) {
        rebound = watch.rebound_until(length * k / 64.0);
    }
    return {watch, rebound};
}

TEST(ResonatorMotion, HeldLongItSettlesAtTheResonatorsSteadyStrengthAtEveryPhase) {
    // Measured at the drive's frequency, the forced motion's amplitude is exactly
    // u / rated x G(f), on resonance and far off it, whatever phase the vibration started at.
    for (const double q : {8.0, 15.0, 25.0}) {
        const Physics physics(example_lra(175.0, q));
        for (const double f : {140.0, 175.0, 220.0}) {
            const Drive hold{0.5, f};
            ResonatorMotion motion;
            motion.change(physics, 0.0, {}, hold);
            const double settled = 20.0 * physics.time_constant_s(hold);
            const double most = motion.strongest(physics, settled, hold, hold, 0.0, hold, 0.01, 16);
            EXPECT_NEAR(most, physics.steady_strength(hold), 1e-6 * physics.steady_strength(hold))
                << "Q " << q << ", " << f << " Hz";
        }
    }
}

TEST(ResonatorMotion, NoPhaseOfTheStartIsWeakerThanBenchFeelsPlantAndTheStrongestIsOne) {
    // The plant starts its carrier at phase 0, one of the phases followed: the strongest of them
    // is at least the plant's at the end, and along the hold as strong as the plant gets there
    // within the spread of the phases' ellipses.
    const Declaration lra = example_lra(175.0, 8.0);
    const Physics physics(lra);
    for (const double f : {140.0, 175.0, 210.0}) {
        const Drive push{1.0, f}, hold{0.5, f};
        const double at = 0.0123;
        for (const double length : {0.002, 0.005, 0.011, 0.030}) {
            ResonatorMotion motion;
            motion.change(physics, 0.0, {}, push);
            const double most = motion.strongest(physics, at, push, push, 0.0, hold, length, 1);
            const std::vector<render::Cue> cues{render::drive_at(0.0, 1.0, f),
                                                render::drive_at(at, 0.5, f)};
            const double rate = 1e6;
            const auto plant = bench::Plant(lra).respond(
                cues, rate, static_cast<std::size_t>(std::round((at + length) * rate)) + 1);
            EXPECT_GE(most, plant.back() - 1e-4) << f << " Hz, " << length << " s";
            // Looked at along the hold (eight times a cycle at the least): against the plant's
            // strongest there.
            const double plant_most = *std::max_element(
                plant.begin() + static_cast<std::ptrdiff_t>(at * rate), plant.end());
            EXPECT_LE(most, 1.5 * plant_most + 0.05) << f << " Hz, " << length << " s";
        }
    }
}

TEST(ResonatorMotion, AVibrationStartingAgainIsJudgedMeetingWhatStillRingsInPhase) {
    // After a silence the drive starts at the backend's phase (gpio-lra starts each waveform
    // afresh), whatever still rings: the strongest the motion says a new note gets is at least
    // what it gets meeting the ringing in phase (the model's envelope so started, less what its
    // looks may miss of a ripple's top), however the first note left the ringing, and at least
    // what bench/feel's plant (whose carrier goes on through the silence) gets.
    const Declaration lra = example_lra(175.0, 8.0);
    const Physics physics(lra);
    const Drive push{1.0, 185.0};
    const double rate = 1e6, length = 0.01;
    for (int k = 0; k < 8; ++k) {
        // Notes ending an eighth of their 10 Hz beat apart leave the ringing at eight phases.
        const double stop = 0.03 + k / (8.0 * 10.0), start = stop + 0.004;
        ResonatorMotion motion;
        motion.change(physics, 0.0, {}, push);
        motion.change(physics, stop, push, {});
        const double most = motion.strongest(physics, start, {}, push, length, push, 0.0, 32);

        const State rung = physics.advance(physics.advance({}, push, stop), {}, start - stop);
        double in_phase = 0.0;
        for (int n = 1; n <= 100; ++n) {
            in_phase = std::max(in_phase, Physics::strength(physics.advance(
                                              {Physics::strength(rung), push.frequency_hz}, push,
                                              length * n / 100.0)));
        }
        EXPECT_GE(most, in_phase - 0.02) << "first note " << stop << " s";

        const auto plant = bench::Plant(lra).respond(
            {render::drive_at(0.0, 1.0, 185.0), render::drive_at(stop, 0.0, 0.0),
             render::drive_at(start, 1.0, 185.0)},
            rate, static_cast<std::size_t>((start + length) * rate) + 1);
        const double plant_most = *std::max_element(
            plant.begin() + static_cast<std::ptrdiff_t>(start * rate), plant.end());
        EXPECT_GE(most, plant_most - 0.02) << "first note " << stop << " s";
    }
}

TEST(ResonatorMotion, ABrakeThatStopsItAtResonanceLeavesNoReboundAndOneThatGoesOnDoes) {
    // At resonance the envelope's brake to rest is exact but for the 1 / 4Q the envelope leaves
    // out: braked for as long as the envelope takes to reach zero, the LRA stays quiet; braked
    // twice as long, it is pushed back up through rest.
    const Physics physics(example_lra(175.0, 15.0));
    const Drive hold{0.7, 0.0}, brake{-1.0, 0.0};
    ResonatorMotion motion;
    motion.change(physics, 0.0, {}, hold);
    const double at = 20.0 * physics.time_constant_s(hold);
    // From strength 1 under full anti-phase (strength 1 / 0.7): zero after tau ln(1 + 0.7).
    const double to_rest = physics.time_constant_s(hold) * std::log(1.0 + 0.7);
    auto exact = motion.braking(physics, at, hold, brake, 0.1);
    double rebound = 0.0;
    for (int k = 1; k <= 32; ++k) {
        rebound = exact.rebound_until(to_rest * k / 32);
    }
    EXPECT_LE(rebound, 0.0);
    auto too_long = motion.braking(physics, at, hold, brake, 0.1);
    for (int k = 1; k <= 64; ++k) {
        rebound = too_long.rebound_until(2.0 * to_rest * k / 64);
    }
    EXPECT_GT(rebound, 0.2);
}

TEST(ResonatorMotion, ABrakeMayTakeItATenthAboveWhereItStartedAndNoFurther) {
    // Held at resonance long enough to settle, then "braked" by a stronger drive at the same
    // frequency and phase: the LRA settles at the two drives' ratio of where it was. A tenth
    // above (the last allowed, a hair under it) is no rebound; a hair over it is. A note far
    // above the quiet level, so the levels' own watch plays no part.
    const Physics physics(example_lra(175.0, 15.0));
    const Drive note{0.5, 175.0};
    const double settled = 20.0 * physics.time_constant_s(note);
    const double edge = 1.0 + ResonatorMotion::Brake::kPushUp;
    for (const double ratio : {edge - 1e-3, edge + 1e-3}) {
        const Drive stronger{note.amplitude * ratio, note.frequency_hz};
        const double rebound =
            braked_after_settling(physics, note, settled, stronger, 0.1 * note.amplitude, settled)
                .second;
        if (ratio < edge) {
            EXPECT_LT(rebound, 0.0) << ratio;
        } else {
            EXPECT_GT(rebound, 0.0) << ratio;
        }
    }
}

TEST(ResonatorMotion, ARiseAfterADipCountsOnlyPastItsSlackAboveTheLevel) {
    // Settled at resonance, then braked in anti-phase by a weak drive for long: the LRA goes
    // through rest (below every level) and settles, reversed, at the brake's own steady strength,
    // where the measure at the drive's frequency no longer wobbles. Settled just under the slack
    // above the lowest level (0.8 x quiet) is no rebound; just over it is. Both are above the
    // level itself, so without the slack both would be.
    const Physics physics(example_lra(175.0, 15.0));
    const Drive note{0.5, 175.0}, brake{-0.05, 175.0};
    const double settled = 20.0 * physics.time_constant_s(note);
    const double reversed = physics.steady_strength(brake);
    const double edge = 1.0 + ResonatorMotion::Brake::kRiseSlack;
    for (const double above : {edge - 2e-3, edge + 2e-3}) {
        const double quiet = reversed / (0.8 * above);
        const double rebound =
            braked_after_settling(physics, note, settled, brake, quiet, settled).second;
        if (above < edge) {
            EXPECT_LT(rebound, 0.0) << above;
        } else {
            EXPECT_GT(rebound, 0.0) << above;
        }
        // Settled: the rise is the brake's strength less the slack's share of the lowest level.
        EXPECT_NEAR(rebound, reversed - 0.8 * quiet * edge, 1e-4 * reversed) << above;
    }
}

TEST(ResonatorMotion, ABrakeLeavingItLouderThanCoastingWouldHasDrivenItOnUnlessBothAreQuiet) {
    // Settled at resonance, then driven on, in phase, at a fraction of the note: long after, it
    // holds at that fraction where coasting would have left nothing. Above the highest level
    // (1.2 x the quiet level, a tenth of the note) that is a brake that drove it on; below, both
    // are quiet. Braked in anti-phase to rest, it is quieter than coasting.
    const Physics physics(example_lra(175.0, 15.0));
    const Drive note{0.5, 175.0};
    const double settled = 20.0 * physics.time_constant_s(note);
    const double strength = physics.steady_strength(note), quiet = 0.1 * strength;
    const auto louder = [&](const Drive& brake, double length) {
        return braked_after_settling(physics, note, settled, brake, quiet, length)
            .first.louder_than_coasting();
    };
    EXPECT_FALSE(louder({0.11 * note.amplitude, 175.0}, settled));
    EXPECT_TRUE(louder({0.13 * note.amplitude, 175.0}, settled));
    // From strength s under full anti-phase (strength 1 / rated): zero after tau ln(1 + s rated).
    const double to_rest = physics.time_constant_s(note) *
                           std::log(1.0 + strength * physics.declaration().rated_drive);
    EXPECT_FALSE(louder({-1.0, 175.0}, to_rest));
    EXPECT_TRUE(louder({0.5 * note.amplitude, 175.0}, to_rest));
}

TEST(ResonatorMotion, WhatABrakeTypicallyLeavesIsTheMotionsRootMeanSquareOverPhasesAndCoastsAway) {
    // Settled at resonance, every phase of the start rings alike: typically as strong as the
    // steady state. Left alone (a brake of nothing), that rings down at the time constant;
    // braked in anti-phase for as long as the envelope takes to rest, next to nothing is left
    // (the little the envelope leaves out).
    const Physics physics(example_lra(175.0, 15.0));
    const Drive note{0.5, 175.0};
    const double settled = 20.0 * physics.time_constant_s(note);
    const double strength = physics.steady_strength(note);
    const double tau = physics.time_constant_s({});
    ResonatorMotion motion;
    motion.change(physics, 0.0, {}, note);
    auto coasting = motion.braking(physics, settled, note, {0.0, 175.0}, 0.1 * strength);
    EXPECT_NEAR(coasting.typical_at_start(), strength, 1e-3 * strength);
    for (const double length : {0.5 * tau, tau, 2.0 * tau}) {
        coasting.look(length);
        EXPECT_NEAR(coasting.typical_left(), strength * std::exp(-length / tau), 2e-3 * strength)
            << length;
        EXPECT_NEAR(coasting.typical_at_start(), strength, 1e-3 * strength);
    }
    const double to_rest = tau * std::log(1.0 + strength * physics.declaration().rated_drive);
    auto braked = motion.braking(physics, settled, note, {-1.0, 175.0}, 0.1 * strength);
    braked.look(to_rest);
    EXPECT_LT(braked.typical_left(), 0.05 * strength);
}

TEST(ResonatorMotion, WhereThePhasesLeaveItUnlikeWhatItTypicallyLeavesIsNotTheWorstPhase) {
    // A note a quarter of a cycle long, far below resonance, leaves a motion that depends on where
    // in the carrier's cycle it started: what the drive forced and the LRA's own ringing add up
    // at some phases and cancel at others. Started at 32 phases on bench/feel's plant (its
    // carrier is at phase 0 at time 0 and goes on through a silence at the note's frequency, so
    // a note after one starts at the phase the silence left) and left to coast: the typical
    // loudness is the root mean square over those phases, and the loudest of them over a third
    // above it (the worst phase would have judged it so).
    const Declaration lra = example_lra(175.0, 8.0);
    const Physics physics(lra);
    const double f = 120.0, length = 0.002;
    const Drive note{0.8, f};
    ResonatorMotion motion;
    motion.change(physics, 0.0, {}, note);
    auto coasting = motion.braking(physics, length, note, {0.0, 175.0}, 0.01);
    constexpr int kStarts = 32;
    const double rate = 1e6;
    for (const double left_for : {0.001, 0.003, 0.008}) {
        coasting.look(left_for);
        double squares = 0.0, loudest = 0.0;
        for (int k = 0; k < kStarts; ++k) {
            const double delay = static_cast<double>(k) / kStarts / f;
            const std::vector<render::Cue> cues{render::drive_at(0.0, 0.0, f),
                                                render::drive_at(delay, note.amplitude, f),
                                                render::drive_at(delay + length, 0.0, 175.0)};
            const auto plant = bench::Plant(lra).respond(
                cues, rate,
                static_cast<std::size_t>(std::round((delay + length + left_for) * rate)) + 1);
            squares += plant.back() * plant.back();
            loudest = std::max(loudest, plant.back());
        }
        const double typical = std::sqrt(squares / kStarts);
        EXPECT_NEAR(coasting.typical_left(), typical, 2e-3 * typical) << left_for << " s";
        EXPECT_GT(loudest, 1.3 * coasting.typical_left()) << left_for << " s";
    }
}

TEST(ResonatorMotion, AnErmHasNoneOfIt) {
    const Physics physics(example_erm());
    ResonatorMotion motion;
    motion.change(physics, 0.0, {}, {1.0, 0.0});
    EXPECT_EQ(motion.strongest(physics, 0.1, {1.0, 0.0}, {-1.0, 0.0}, 0.01, {}, 0.01, 4), 0.0);
    auto brake = motion.braking(physics, 0.1, {1.0, 0.0}, {-1.0, 0.0}, 0.1);
    EXPECT_LT(brake.rebound_until(0.05), 0.0);
}

}  // namespace
}  // namespace vibscore::actuator
