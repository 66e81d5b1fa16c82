#include "actuator/declaration.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <string>

#include "actuator/physics.hpp"
#include "common/above_zero.hpp"
#include "common/closest_name.hpp"
#include "common/ini_reader.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"

namespace vibscore::actuator {

namespace {

std::string at(const std::string& where) {
    return where.empty() ? std::string() : where + ": ";
}

// "Above 0" is common/above_zero.hpp's rule: subnormals are refused with 0.
bool above(double value, const Limit& limit) {
    return limit.min == 0.0 ? above_zero(value) : value > limit.min;
}

std::string range_text(const Limit& limit) {
    if (limit.min_allowed) {
        return "a number from " + number_text(limit.min) + " to " + number_text(limit.max);
    }
    return "a number above " + number_text(limit.min) + " and at most " + number_text(limit.max) +
           (limit.min == 0.0 ? " (at least " + number_text(kSmallestAboveZero) + ")" : "");
}

std::string key_value(const Setting& setting) {
    return at(setting.where) + "[actuator] " + shown_text(setting.key) + " = " +
           quoted_text(setting.value);
}

double number(const Setting& setting, const Limit& limit) {
    const auto value = ini_number(setting.value);
    if (!value || !(limit.min_allowed ? *value >= limit.min : above(*value, limit)) ||
        *value > limit.max) {
        throw DeclarationError(setting.key, key_value(setting) + ": expected " + range_text(limit));
    }
    return *value;
}

std::string choice(const Setting& setting, std::initializer_list<const char*> allowed) {
    std::string names;
    for (const char* option : allowed) {
        if (setting.value == option) {
            return setting.value;
        }
        names += (names.empty() ? "" : " or ") + std::string(option);
    }
    throw DeclarationError(setting.key, key_value(setting) + ": expected " + names);
}

bool is_key(const std::string& key) {
    return std::any_of(std::begin(kKeys), std::end(kKeys),
                       [&](const char* known) { return key == known; });
}

// The keys that describe one kind's physics only.
bool erm_only(const std::string& key) {
    return key == kSpinUpMs.key || key == kSpinDownMs.key;
}
bool lra_only(const std::string& key) {
    return key == kResonanceHz.key || key == kQ.key || key == kResonanceTolerancePercent.key ||
           key == kQTolerancePercent.key;
}

// Where the declared model stops being finite, or nothing. Each number is within its limits,
// but together they may still overflow: a strength is a drive divided by rated-drive, and a tiny
// rated-drive makes it (or the LRA's forcing, or its square) infinite, and then NaN. Probed at
// the model's extremes: full drive forwards and backwards at the actuator's own frequency and
// far off it, from rest and from the opposite steady state, over short and long steps.
std::optional<std::string> model_fault(const Declaration& declaration) {
    const Physics physics(declaration);
    const auto fault = [](const char* what, double frequency_hz, double value) {
        return std::string(what) + " under full drive at " +
               (frequency_hz == 0.0 ? std::string("its own frequency")
                                    : number_text(frequency_hz) + " Hz") +
               " is " + number_text(value);
    };
    const double f0 = declaration.resonance_hz;
    for (const double frequency : {0.0, 1.0, f0 / 2, f0 * 2, 20000.0}) {
        for (const double amplitude : {1.0, -1.0}) {
            const Drive drive{amplitude, frequency};
            const double steady = physics.steady_strength(drive);
            if (!std::isfinite(steady)) {
                return fault("the steady strength", frequency, steady);
            }
            if (const double tau = physics.time_constant_s(drive); !std::isfinite(tau)) {
                return fault("the time constant", frequency, tau);
            }
            const State opposite = physics.advance({}, {-amplitude, frequency}, 10.0);
            for (const State& from : {State{}, opposite}) {
                for (const double dt : {1e-4, 1e-2, 1.0}) {
                    const State next = physics.advance(from, drive, dt);
                    const double strength = Physics::strength(next);
                    if (!std::isfinite(next.envelope.real()) ||
                        !std::isfinite(next.envelope.imag())) {
                        return fault("the strength", frequency, strength);
                    }
                    // Where the strength is headed is told by |z|^2's derivative.
                    if (!std::isfinite(strength * strength)) {
                        return fault("the strength", frequency, strength) +
                               ", and its square overflows";
                    }
                }
                const auto reach = physics.time_to(from, drive, steady / 2, 0.1);
                if (!std::isfinite(reach.after_s)) {
                    return fault("the time to half strength", frequency, reach.after_s);
                }
            }
        }
    }
    return std::nullopt;
}

}  // namespace

double lra_time_constant_s(double resonance_hz, double q) {
    return q / (std::numbers::pi * resonance_hz);
}

Declaration parse_declaration(const std::vector<Setting>& settings,
                              const std::string& section_where) {
    std::map<std::string, const Setting*> by_key;
    for (const Setting& setting : settings) {
        if (!is_key(setting.key)) {
            std::vector<std::string> known(std::begin(kKeys), std::end(kKeys));
            std::string list;
            for (const auto& key : known) {
                list += (list.empty() ? "" : ", ") + key;
            }
            const auto meant = closest_name(setting.key, known);
            throw DeclarationError(
                setting.key,
                at(setting.where) + "unknown key " + quoted_text(setting.key) + " in [actuator]" +
                    (meant ? " (did you mean " + *meant + "?)" : "") + "; known: " + list);
        }
        if (setting.value.empty()) {
            throw DeclarationError(setting.key, at(setting.where) + "[actuator] " +
                                                    shown_text(setting.key) + " has no value");
        }
        const auto [previous, added] = by_key.emplace(setting.key, &setting);
        if (!added) {
            throw DeclarationError(setting.key,
                                   at(setting.where) + "[actuator] " + shown_text(setting.key) +
                                       " is set twice (first at " + previous->second->where + ")");
        }
    }
    const auto find = [&](const char* key) -> const Setting* {
        const auto found = by_key.find(key);
        return found == by_key.end() ? nullptr : found->second;
    };

    Declaration declaration;
    const Setting* kind = find("kind");
    if (kind == nullptr) {
        throw DeclarationError("kind", at(section_where) + "[actuator] needs kind = erm or lra");
    }
    declaration.kind = choice(*kind, {"erm", "lra"}) == "erm" ? Kind::erm : Kind::lra;
    for (const auto& [key, setting] : by_key) {
        const bool wrong_kind = declaration.kind == Kind::erm ? lra_only(key) : erm_only(key);
        if (wrong_kind) {
            throw DeclarationError(key, key_value(*setting) + " is for kind = " +
                                            (declaration.kind == Kind::erm ? "lra" : "erm") +
                                            "; this actuator is kind = " + kind->value);
        }
    }
    if (const Setting* s = find(kRatedDrive.key)) {
        declaration.rated_drive = number(*s, kRatedDrive);
    }
    if (const Setting* s = find(kSpinUpMs.key)) {
        declaration.spin_up_s = number(*s, kSpinUpMs) / 1000.0;
    }
    if (const Setting* s = find(kSpinDownMs.key)) {
        declaration.spin_down_s = number(*s, kSpinDownMs) / 1000.0;
    }
    if (const Setting* s = find(kResonanceHz.key)) {
        declaration.resonance_hz = number(*s, kResonanceHz);
    }
    if (const Setting* s = find(kQ.key)) {
        declaration.q = number(*s, kQ);
    }
    if (const Setting* s = find(kResonanceTolerancePercent.key)) {
        declaration.resonance_tolerance = number(*s, kResonanceTolerancePercent) / 100.0;
    }
    if (const Setting* s = find(kQTolerancePercent.key)) {
        declaration.q_tolerance = number(*s, kQTolerancePercent) / 100.0;
    }
    if (const Setting* s = find("brake")) {
        declaration.brake =
            choice(*s, {"none", "reverse"}) == "none" ? Brake::none : Brake::reverse;
    }
    if (const Setting* s = find("compensation")) {
        declaration.compensation = choice(*s, {"on", "off"}) == "on";
    }
    if (const auto fault = model_fault(declaration)) {
        const Setting* s = find(kRatedDrive.key);
        throw DeclarationError(
            kRatedDrive.key,
            (s != nullptr ? key_value(*s) : at(section_where) + "[actuator]") +
                ": the actuator's model is not finite with it (" + *fault +
                "); a rated-drive this small is no actuator: give the drive it is rated for");
    }
    return declaration;
}

std::optional<Section> find_section(const std::vector<IniLine>& lines) {
    std::optional<Section> section;
    for (const IniLine& line : lines) {
        if (line.section != kSection) {
            continue;
        }
        if (!section) {
            section = Section{{}, line.where};
        }
        if (!line.is_header()) {
            section->settings.push_back({line.key, line.value, line.where});
        }
    }
    return section;
}

std::optional<Section> find_section(const std::string& text, const std::string& file) {
    try {
        return find_section(read_ini(text, file));
    } catch (const IniError& error) {
        throw DeclarationError({}, error.what());
    }
}

std::optional<Declaration> read_declaration(const std::string& text, const std::string& file) {
    const auto section = find_section(text, file);
    if (!section) {
        return std::nullopt;
    }
    return parse_declaration(section->settings, section->where);
}

Declaration from_settings(const std::map<std::string, std::string>& settings,
                          const std::string& source) {
    std::vector<Setting> lines;
    for (const auto& [key, value] : settings) {
        lines.push_back({key, value, source});
    }
    return parse_declaration(lines, source);
}

std::vector<std::pair<std::string, std::string>> to_settings(const Declaration& declaration) {
    std::vector<std::pair<std::string, std::string>> settings;
    const bool erm = declaration.kind == Kind::erm;
    settings.emplace_back("kind", erm ? "erm" : "lra");
    settings.emplace_back(kRatedDrive.key, number_text(declaration.rated_drive));
    if (erm) {
        settings.emplace_back(kSpinUpMs.key, number_text(declaration.spin_up_s * 1000.0));
        settings.emplace_back(kSpinDownMs.key, number_text(declaration.spin_down_s * 1000.0));
    } else {
        settings.emplace_back(kResonanceHz.key, number_text(declaration.resonance_hz));
        settings.emplace_back(kQ.key, number_text(declaration.q));
        const Declaration defaults;
        if (declaration.resonance_tolerance != defaults.resonance_tolerance) {
            settings.emplace_back(kResonanceTolerancePercent.key,
                                  number_text(declaration.resonance_tolerance * 100.0));
        }
        if (declaration.q_tolerance != defaults.q_tolerance) {
            settings.emplace_back(kQTolerancePercent.key,
                                  number_text(declaration.q_tolerance * 100.0));
        }
    }
    settings.emplace_back("brake", declaration.brake == Brake::reverse ? "reverse" : "none");
    settings.emplace_back("compensation", declaration.compensation ? "on" : "off");
    return settings;
}

std::string describe(const Declaration& declaration) {
    std::string text;
    if (declaration.kind == Kind::erm) {
        text = "erm: spin-up " + number_text(declaration.spin_up_s * 1000.0) + " ms, spin-down " +
               number_text(declaration.spin_down_s * 1000.0) + " ms";
    } else {
        const double tau_ms = lra_time_constant_s(declaration.resonance_hz, declaration.q) * 1000.0;
        text = "lra: resonance " + number_text(declaration.resonance_hz) + " Hz, q " +
               number_text(declaration.q) + " (envelope " +
               number_text(std::round(tau_ms * 10.0) / 10.0) + " ms)";
    }
    return text + ", rated-drive " + number_text(declaration.rated_drive) + ", brake " +
           (declaration.brake == Brake::reverse ? "reverse" : "none") + ", compensation " +
           (declaration.compensation ? "on" : "off");
}

}  // namespace vibscore::actuator
