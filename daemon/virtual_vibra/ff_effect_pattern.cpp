#include "daemon/virtual_vibra/ff_effect_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vibscore::daemon {

namespace {

constexpr double kRumbleFull = 0xffff;
constexpr double kLevelFull = 0x7fff;  // periodic magnitude, constant level, envelope levels

double level_of(int value) {
    return std::min(std::abs(value) / kLevelFull, 1.0);
}

// The strength and envelope an effect asks for, before timing.
struct Strength {
    double magnitude = 0.0;
    const ff_envelope* envelope = nullptr;  // periodic and constant effects only
    double frequency_hz = 0.0;
};

Strength strength_of(const ff_effect& effect) {
    switch (effect.type) {
        case FF_RUMBLE:
            return {std::max(effect.u.rumble.strong_magnitude, effect.u.rumble.weak_magnitude) /
                        kRumbleFull,
                    nullptr, 0.0};
        case FF_CONSTANT:
            return {level_of(effect.u.constant.level), &effect.u.constant.envelope, 0.0};
        case FF_PERIODIC: {
            const auto& periodic = effect.u.periodic;
            if (periodic.waveform != FF_SINE && periodic.waveform != FF_SQUARE &&
                periodic.waveform != FF_TRIANGLE) {
                throw std::invalid_argument("periodic waveform " +
                                            std::to_string(periodic.waveform) +
                                            " (only sine, square and triangle)");
            }
            const double hz = periodic.period > 0 ? 1000.0 / periodic.period : 0.0;
            const bool in_band = hz >= kMinEffectFrequencyHz && hz <= kMaxEffectFrequencyHz;
            return {level_of(periodic.magnitude), &periodic.envelope, in_band ? hz : 0.0};
        }
        default:
            throw std::invalid_argument("effect type " + std::to_string(effect.type) +
                                        " (only rumble, periodic and constant)");
    }
}

const char* waveform_name(int waveform) {
    switch (waveform) {
        case FF_SQUARE:
            return "square";
        case FF_TRIANGLE:
            return "triangle";
        default:
            return "sine";
    }
}

}  // namespace

VibrationPattern ff_effect_pattern(const ff_effect& effect) {
    const Strength strength = strength_of(effect);
    const double m = strength.magnitude;
    const double f = strength.frequency_hz;
    const bool forever = effect.replay.length == 0;
    const double length = !forever                  ? effect.replay.length / 1000.0
                          : ff_effect_loops(effect) ? 1.0
                                                    : kUntilStoppedSeconds;
    double attack = 0.0, attack_level = m, fade = 0.0, fade_level = m;
    if (strength.envelope != nullptr) {
        attack = strength.envelope->attack_length / 1000.0;
        attack_level = level_of(strength.envelope->attack_level);
        // ff-memless fades only effects that end.
        if (!forever) {
            fade = strength.envelope->fade_length / 1000.0;
            fade_level = level_of(strength.envelope->fade_level);
        }
    }
    VibrationPattern pattern;
    if (effect.replay.delay > 0) {
        pattern.push_back({effect.replay.delay / 1000.0, 0.0, 0.0, 0.0});
    }
    // ff-memless: the attack ramp first; the fade ramp over the last `fade` seconds, as far as
    // the attack leaves it, at the level the fade has reached by then.
    const double attack_end = std::min(attack, length);
    if (attack_end > 0.0) {
        pattern.push_back(
            {attack_end, attack_level, attack_level + (m - attack_level) * attack_end / attack, f});
    }
    const double fade_start = std::max(attack_end, length - fade);
    if (fade_start > attack_end) {
        pattern.push_back({fade_start - attack_end, m, m, f});
    }
    if (length > fade_start) {
        const double from = m + (fade_level - m) * (fade_start - (length - fade)) / fade;
        pattern.push_back({length - fade_start, from, fade_level, f});
    }
    return pattern;
}

bool ff_effect_loops(const ff_effect& effect) {
    const Strength strength = strength_of(effect);
    const bool attack = strength.envelope != nullptr && strength.envelope->attack_length > 0;
    return effect.replay.length == 0 && effect.replay.delay == 0 && !attack;
}

std::string describe_ff_effect(const ff_effect& effect) {
    std::string text;
    switch (effect.type) {
        case FF_RUMBLE:
            text = "rumble";
            break;
        case FF_CONSTANT:
            text = "constant";
            break;
        case FF_PERIODIC:
            text = std::string("periodic ") + waveform_name(effect.u.periodic.waveform) + " " +
                   std::to_string(effect.u.periodic.period) + " ms period";
            break;
        default:
            text = "type " + std::to_string(effect.type);
    }
    text += effect.replay.length == 0 ? " until stopped"
                                      : " " + std::to_string(effect.replay.length) + " ms";
    if (effect.replay.delay > 0) {
        text += " after " + std::to_string(effect.replay.delay) + " ms";
    }
    return text;
}

}  // namespace vibscore::daemon
