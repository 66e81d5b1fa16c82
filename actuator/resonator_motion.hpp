#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <utility>

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
// vibration starts it is the backend's (gpio-lra starts each waveform afresh). Being linear, the
// motion for every phase phi of that start is two numbers (one turning with e^(i phi), one
// against it), followed once: the strongest is then exact over every phase, and a brake is
// judged by the worst of kPhases of them. Each vibration starts at a phase of its own, though,
// so how strong what earlier ones left may be is kept too, for how strong a new one may get
// meeting it.
class ResonatorMotion {
  public:
    // Every call passes the same actuator (a planner's own, which may be moved).

    // At `t`, the drive `to` replaces `from` (the one in force since the last change).
    void change(const Physics& physics, double t, const Drive& from, const Drive& to);

    // A brake is judged at this many phases of the start of its vibrations: between them its
    // strength may dip below a level and rise again (a 0.55 note at 263 Hz on a 235 Hz Q-8 LRA,
    // braked at 202 Hz, judged at 24 phases, rose again to 10.9 % at a phase between two).
    static constexpr int kPhases = 96;
    // What rang before a vibration started meets its brake at this many phases, and at this
    // many strengths up to the most it may be (a brake's rebound need not grow with it).
    static constexpr int kRingingPhases = 8;
    static constexpr int kRingingLevels = 2;

  private:
    // The motion for every phase phi at which a vibration starts, at once: the resonator is
    // linear, so w(phi) = with e^(i phi) + against e^(-i phi), the carrier being
    // carrier e^(i phi).
    struct Phased {
        std::complex<double> with{}, against{};
        std::complex<double> carrier{1.0, 0.0};
    };
    struct Now {
        // The whole motion, each start of a vibration at the same phase.
        Phased motion{};
        // The vibration going on alone, from rest, and the most that what rang before it may
        // ring (|w|): each earlier vibration started at a phase of its own, so what each left may
        // meet the others' in phase.
        Phased own{};
        double before = 0.0;
    };
    // How a motion measures at one frequency: x + i v / omega is a w + b conj(w).
    struct Measure {
        std::complex<double> a, b;
        // At phase phi of a Phased: first e^(i phi) + second e^(-i phi).
        std::pair<std::complex<double>, std::complex<double>> of(const Phased& p) const {
            return {a * p.with + b * std::conj(p.against), a * p.against + b * std::conj(p.with)};
        }
        std::complex<double> of(std::complex<double> w) const { return a * w + b * std::conj(w); }
        // The most a |w| of `ringing` measures, at whatever phase it rings.
        double loudest(double ringing) const { return ringing * (std::abs(a) + std::abs(b)); }
    };

  public:
    // A brake followed as it goes on, for each phase, for a rebound: once the LRA has been below
    // a level, how far above that level it gets again (past rest a brake adds energy); for each
    // of kLevels levels from `quiet` x 0.8 to x 1.2, so that one a little off still holds. It
    // keeps the actuator by reference: it lives no longer than the planning step that made it.
    static constexpr int kLevels = 5;
    class Brake {
      public:
        // Follows the brake on to `length` (increasing from call to call), for each phase and
        // level keeping the least it has been and how far above the level it has risen since.
        void look(double length);
        // The most any phase has been above a level after being below it, in strength units
        // (negative: never), over every look so far; positive too where a phase has gone more
        // than kPushUp above its strength at the brake's start (and above the highest level):
        // that brake adds energy instead of taking it.
        double rebound() const { return rebound_; }
        // For the brake ending at the last look, the most any phase that has been below a level
        // is above it there as measured left to ring at the LRA's own frequency.
        double rebound_left() const;
        // look(length), then the larger of rebound() and rebound_left().
        double rebound_until(double length);
        static constexpr double kPushUp = 0.10;
        // A rise counts past this much of the level: the measure of a motion that turns at
        // the LRA's own frequency, taken at another, wobbles at twice it (a full-scale brake on
        // a 175 Hz Q-15 LRA at its resonance, looked at sixteen times a ripple, dips below quiet
        // and comes back 0.5 % of it above, 0.05 % of the note).
        static constexpr double kRiseSlack = 0.01;
        // Whether the brake, ending at the last `length` looked at, leaves the whole motion at
        // some phase louder than coasting would, and above the highest level (both quiet is
        // quiet): it has driven the LRA on rather than stopped it.
        bool louder_than_coasting() const;
        // Whether some phase has already risen again (or past its ceiling), wherever the brake
        // ends: longer looks cannot take that back.
        bool has_rebounded() const { return rebound_ > 0.0; }
        // How loud the whole motion typically is, left to ring at the LRA's own frequency, over
        // the phases its vibrations may have started at (the root mean square over them): from
        // the last look, and where the brake started. Which phase the backend started at is not
        // known, so a brake that leaves no phase rebounding is chosen by what it typically
        // leaves; the worst phase is the rebound's to judge.
        double typical_left() const;
        double typical_at_start() const;

      private:
        friend class ResonatorMotion;
        Brake(const Physics& physics, const Now& now, const Drive& drive, double quiet);
        // How one motion of the watch measures at phase phi: |first e^(i phi) +
        // second e^(-i phi) + ringing|.
        struct Seen;
        // Calls `judge(group, as measured under the brake, as left to ring)` for the whole
        // motion (group 0) and, where what rang before the vibration is more than a hundredth
        // of the quiet level, for the vibration alone with that ringing at each of
        // kRingingPhases phases and kRingingLevels strengths up to its most (groups 1 on);
        // each group is kPhases phases.
        template <class Judge>
        void each(Judge judge) const;
        // The most any phase (or one between two) rises above a level once below it (less
        // kRiseSlack), `loudness(k)` being how loud phase k of `group` is.
        template <class Loudness>
        double rise(int group, Loudness loudness) const;
        static constexpr int kRingings = kRingingPhases * kRingingLevels;
        static constexpr int kGroups = 1 + kRingings;
        static constexpr int kMost = kPhases * kGroups;
        const Physics* physics_;
        Phased whole_, own_;
        std::array<std::complex<double>, kRingings> ringing_{};
        int ringings_ = 0;
        Drive drive_;
        Measure driven_{}, resting_{};
        std::array<double, kLevels> levels_{};
        std::array<double, kMost> ceiling_{};  // the most each may reach while braked
        std::array<double, kMost> lowest_{};   // the least each has been, from the brake's start
        std::array<double, kGroups> lowest_ceiling_{};
        std::array<bool, kGroups> any_below_{};
        Phased start_;  // the whole motion where the brake starts, to coast from instead
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
    static void advance(const Physics& physics, Phased& motion, const Drive& drive, double dt);
    // Where a vibration starts (at a phase of the backend's: gpio-lra starts each waveform
    // afresh), the motion goes on from each phase, and what the last one left ringing joins
    // what rang before it.
    static void start(Now& now);
    // What it would be at `t` had `to` replaced `from` there.
    Now replaced_at(const Physics& physics, double t, const Drive& from, const Drive& to) const;
    // The amplitude of x measured at `frequency_hz` as bench/feel's plant does (driven: the
    // drive's; left alone: the resonance).
    static Measure measure(const Physics& physics, double frequency_hz);

    Now now_;
    double time_ = 0.0;
};

}  // namespace vibscore::actuator
