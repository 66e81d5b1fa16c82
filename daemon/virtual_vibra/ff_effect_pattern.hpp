#pragma once

#include <linux/input.h>

#include <string>

#include "score/pattern_score.hpp"

// What a force-feedback effect asks of a vibrator, as a pattern of strengths (then a score, as
// score/pattern_score.hpp writes it): the Linux FF model of include/uapi/linux/input.h with the
// envelope and replay rules of the kernel's ff-memless, which drives most phone vibras.
namespace vibscore::daemon {

// Periods the virtual vibra plays as a frequency; longer or shorter ones (a slow wobble, or
// none at all) play at the actuator's own frequency, as ff-memless plays every period.
inline constexpr double kMinEffectFrequencyHz = 20.0;
inline constexpr double kMaxEffectFrequencyHz = 1000.0;

// One replay of `effect`: its delay as a pause, then its strength for its length: FF_RUMBLE the
// stronger of its two motors (of 0xffff); FF_PERIODIC (sine, square or triangle, all played as
// a vibration at 1000/period Hz) and FF_CONSTANT their magnitude or level (of 0x7fff), with the
// envelope's attack ramp from its start and fade ramp to its end. A length of 0 means until
// stopped: when ff_effect_loops(), one second of the strength, to be played over and over;
// otherwise (a delay or an attack comes first) the strength is held for
// kUntilStoppedSeconds. Throws std::invalid_argument for anything else (other types,
// waveforms, custom data).
VibrationPattern ff_effect_pattern(const ff_effect& effect);

// An effect until stopped with neither delay nor attack: a steady strength, which loops exactly.
bool ff_effect_loops(const ff_effect& effect);

// How long an effect "until stopped" holds when it cannot loop. The renderer follows a held
// note in small steps, so an hour would keep the daemon's loop busy for a fifth of a second on
// each play; ten minutes cost a few milliseconds.
inline constexpr double kUntilStoppedSeconds = 600.0;

// "rumble 150 ms", "periodic sine 100 Hz 10000 ms", "constant forever": for logs and labels.
std::string describe_ff_effect(const ff_effect& effect);

}  // namespace vibscore::daemon
