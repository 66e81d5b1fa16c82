#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <span>

#include "actuator/physics.hpp"

namespace vibscore::actuator {

// An LRA's whole motion under the drives sent, exactly, to judge a brake by: Physics' envelope
// leaves out a little of it (a few % of a note near resonance), and that little is what stays
// when the envelope says a brake has stopped the LRA: up to 20 % of a note after a full-scale
// brake far off a Q-8 LRA's resonance, on bench/feel's plant. The envelope drops the half of the
// drive that turns against the resonator, and its amplitude off resonance is the forced motion's,
// not the part of it that turns like the resonator's own ringing; both show at every change of
// drive, and most where a brake meets rest.
//
// The resonator x'' + 2g x' + w0^2 x = F u cos(theta) is, in w = x' - l- x (l+- = -g +- i wd),
// the first-order w' = l+ w + F u cos(theta), solved in closed form between changes. What it does
// depends on the carrier's phase: the backends continue it from drive to drive, but where a
// vibration starts it is the backend's (gpio-lra starts each waveform afresh), so the motion is
// followed for kPhases phases of that start, and a brake is judged by the worst of them. Each
// vibration starts at a phase of its own, though, so how strong what earlier ones left may be
// is kept too, for how strong a new one may get meeting it.
class ResonatorMotion {
  public:
    // Every call passes the same actuator (a planner's own, which may be moved).

    // At `t`, the drive `to` replaces `from` (the one in force since the last change).
    void change(const Physics& physics, double t, const Drive& from, const Drive& to);

    static constexpr int kPhases = 24;
    // What rang before a vibration started meets its brake at this many phases, and at this
    // many strengths up to the most it may be (a brake's rebound need not grow with it).
    static constexpr int kRingingPhases = 8;
    static constexpr int kRingingLevels = 2;

  private:
    struct Motion {
        std::complex<double> w{};
        std::complex<double> carrier{1.0, 0.0};  // e^(i theta)
    };
    using Motions = std::array<Motion, kPhases>;
    struct Now {
        // The whole motion, each start of a vibration at the same phase k / kPhases.
        Motions motions{};
        // The vibration going on alone, from rest at each phase of its start, and the most that
        // what rang before it may ring (|w|): each earlier vibration started at a phase of its
        // own, so what each left may meet the others' in phase.
        Motions own{};
        double before = 0.0;
    };

  public:
    // A brake followed as it goes on, for each phase, for a rebound: once the LRA has been below
    // a level, how far above that level it gets again (past rest a brake adds energy); for each
    // of kLevels levels from `quiet` x 0.8 to x 1.2, so that one a little off still holds. It
    // keeps the actuator by reference: it lives no longer than the planning step that made it.
    static constexpr int kLevels = 5;
    class Brake {
      public:
        // The most any phase has been above a level after being below it, in strength units
        // (negative: never), looked at at every call so far (increasing `length`s) and, for a
        // brake ending at `length`, once it is left to ring at its own frequency; positive too
        // where a phase has gone more than kPushUp above its strength at the brake's start (and
        // above the highest level): that brake adds energy instead of taking it.
        double rebound_until(double length);
        static constexpr double kPushUp = 0.10;
        // Whether the brake, ending at the last `length` looked at, leaves the whole motion at
        // some phase louder than coasting would, and above the highest level (both quiet is
        // quiet): it has driven the LRA on rather than stopped it.
        bool louder_than_coasting() const;

      private:
        friend class ResonatorMotion;
        Brake(const Physics& physics, const Now& now, const Drive& drive, double quiet);
        // The whole motion at each phase and, where what rang before the vibration is more than
        // a hundredth of the quiet level, the vibration alone with that ringing at each of
        // kRingingPhases phases and kRingingLevels strengths up to its most.
        static constexpr int kMost = kPhases * (1 + kRingingPhases * kRingingLevels);
        const Physics* physics_;
        std::array<Motion, kMost> motions_;
        int count_ = kPhases;
        Drive drive_;
        std::array<double, kLevels> levels_{};
        std::array<double, kMost> ceiling_{};  // the most each may reach while braked
        std::array<std::array<bool, kLevels>, kMost> below_{};
        Motions start_;  // the whole motion where the brake starts, to coast from instead
        double length_ = 0.0;
        double rebound_ = -INFINITY;
    };
    // The strongest any phase gets (measured at the drive's frequency) if at `t` the drive `from`
    // in force were replaced by `first` for `first_s` and then by `then` for `then_s`, looked at
    // `looks` times over each (and eight times a cycle of its drive at the least): an overdrive
    // and the hold after it, starting at every phase of the carrier, with what rang before
    // met where the two add up.
    double strongest(const Physics& physics, double t, const Drive& from, const Drive& first,
                     double first_s, const Drive& then, double then_s, int looks) const;

    // At `t`, the drive `from` in force replaced by `brake`, watched for a rebound around
    // `quiet`.
    Brake braking(const Physics& physics, double t, const Drive& from, const Drive& brake,
                  double quiet) const;

  private:
    static void advance(const Physics& physics, std::span<Motion> motions, const Drive& drive,
                        double dt);
    // Where a vibration starts (at a phase of the backend's: gpio-lra starts each waveform
    // afresh), each motion goes on from its own phase k / kPhases, and what the last one left
    // ringing joins what rang before it.
    static void start(Now& now);
    // What it would be at `t` had `to` replaced `from` there.
    Now replaced_at(const Physics& physics, double t, const Drive& from, const Drive& to) const;
    // The amplitude of x, measured at `frequency_hz` as bench/feel's plant does (driven: the
    // drive's; left alone: the resonance).
    static double strength(const Physics& physics, const Motion& motion, double frequency_hz);
    // The most `ringing` (|w|) measures at `frequency_hz`, at whatever phase it rings.
    static double strength_of_ringing(const Physics& physics, double ringing, double frequency_hz);

    Now now_;
    double time_ = 0.0;
};

}  // namespace vibscore::actuator
