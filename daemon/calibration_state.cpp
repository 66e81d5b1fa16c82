#include "daemon/calibration_state.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/ini_reader.hpp"
#include "common/log.hpp"
#include "common/number_text.hpp"
#include "common/trim.hpp"
#include "daemon/config.hpp"

namespace vibscore::daemon {

namespace {

using actuator::Kind;

// A number within [actuator]'s limit for `limit.key`, scaled from the key's units.
double limited(const actuator::Limit& limit, const std::string& value, const std::string& where) {
    const auto parsed = ini_number(value);
    if (!parsed) {
        throw std::invalid_argument(where + ": " + limit.key + " = \"" + value +
                                    "\" is not a number");
    }
    const double number = *parsed;
    const bool low = limit.min_allowed ? number < limit.min : number <= limit.min;
    if (low || number > limit.max) {
        throw std::invalid_argument(where + ": " + limit.key + " = \"" + value + "\" is outside " +
                                    number_text(limit.min) + ".." + number_text(limit.max));
    }
    return number;
}

}  // namespace

MeasuredActuator measured_from(const actuator::calibration::Estimate& estimate,
                               std::string measured_at) {
    MeasuredActuator measured;
    // Rounded as the state file keeps them (below), so the numbers in use are the same before
    // and after a restart.
    measured.kind = estimate.kind;
    if (estimate.kind == Kind::erm) {
        measured.spin_up_s = estimate.spin_up_s;
        measured.spin_down_s = estimate.spin_down_s;
    } else {
        measured.resonance_hz = estimate.resonance_hz;
        measured.q = estimate.q;
    }
    measured.measured_at = std::move(measured_at);
    return parse_measured(measured_text(measured), "the estimate");
}

std::string measured_text(const MeasuredActuator& measured) {
    std::ostringstream text;
    text << "# The actuator as vibscore calibrate --apply measured it (docs/daemon.md,\n"
            "# \"Calibration\"): vibscored uses these numbers in place of the declared ones.\n"
            "# Delete this file (and restart or reload vibscored) to use the declaration again.\n"
         << "measured = " << measured.measured_at << "\n"
         << "kind = " << (measured.kind == Kind::erm ? "erm" : "lra") << "\n";
    const auto line = [&](const char* key, const std::optional<double>& value, double scale) {
        if (value) {
            // Five digits: finer than any estimate is sure of (0.4 % of a resonance at best).
            text << key << " = " << rounded_text(*value * scale, 5) << "\n";
        }
    };
    line(actuator::kSpinUpMs.key, measured.spin_up_s, 1000.0);
    line(actuator::kSpinDownMs.key, measured.spin_down_s, 1000.0);
    line(actuator::kResonanceHz.key, measured.resonance_hz, 1.0);
    line(actuator::kQ.key, measured.q, 1.0);
    return text.str();
}

MeasuredActuator parse_measured(const std::string& text, const std::string& file) {
    MeasuredActuator measured;
    std::optional<Kind> kind;
    std::istringstream lines(text);
    std::string raw;
    int number = 0;
    while (std::getline(lines, raw)) {
        ++number;
        const std::string where = file + ":" + std::to_string(number);
        const std::string content = trim(raw);
        if (content.empty() || content.front() == '#') {
            continue;
        }
        const auto equals = content.find('=');
        if (equals == std::string::npos) {
            throw std::invalid_argument(where + ": expected \"key = value\", found \"" + content +
                                        "\"");
        }
        const std::string key = trim(content.substr(0, equals));
        const std::string value = trim(content.substr(equals + 1));
        if (key == "measured") {
            measured.measured_at = value;
        } else if (key == "kind") {
            if (value != "erm" && value != "lra") {
                throw std::invalid_argument(where + ": kind = \"" + value +
                                            "\" (expected erm or lra)");
            }
            kind = value == "erm" ? Kind::erm : Kind::lra;
        } else if (key == actuator::kSpinUpMs.key) {
            measured.spin_up_s = limited(actuator::kSpinUpMs, value, where) / 1000.0;
        } else if (key == actuator::kSpinDownMs.key) {
            measured.spin_down_s = limited(actuator::kSpinDownMs, value, where) / 1000.0;
        } else if (key == actuator::kResonanceHz.key) {
            measured.resonance_hz = limited(actuator::kResonanceHz, value, where);
        } else if (key == actuator::kQ.key) {
            measured.q = limited(actuator::kQ, value, where);
        } else {
            throw std::invalid_argument(where + ": unknown key \"" + key + "\"");
        }
    }
    if (!kind) {
        throw std::invalid_argument(file + ": no kind = erm|lra");
    }
    if (measured.measured_at.empty()) {
        throw std::invalid_argument(file + ": no measured = DATE");
    }
    measured.kind = *kind;
    const bool erm_keys = measured.spin_up_s || measured.spin_down_s;
    const bool lra_keys = measured.resonance_hz || measured.q;
    if ((*kind == Kind::erm && lra_keys) || (*kind == Kind::lra && erm_keys)) {
        throw std::invalid_argument(file + ": numbers of the other kind for a measured " +
                                    (*kind == Kind::erm ? "erm" : "lra"));
    }
    if (!erm_keys && !lra_keys) {
        throw std::invalid_argument(file + ": no measured number");
    }
    return measured;
}

void save_measured(const std::filesystem::path& file, const MeasuredActuator& measured) {
    write_file_atomically(file, measured_text(measured), 0644);
}

std::optional<MeasuredActuator> load_measured(const std::filesystem::path& file) {
    std::error_code error;
    if (!std::filesystem::exists(file, error)) {
        return std::nullopt;
    }
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in && !in.eof()) {
        log::warning("calibration: cannot read " + file.string() + ": " + std::strerror(errno) +
                     "; using the declared actuator");
        return std::nullopt;
    }
    try {
        return parse_measured(text.str(), file.string());
    } catch (const std::invalid_argument& bad) {
        log::warning(std::string("calibration: ignoring ") + bad.what() +
                     "; using the declared actuator (the file is left as it is: run vibscore "
                     "calibrate --apply again, or delete it)");
        return std::nullopt;
    }
}

actuator::Declaration with_measured(actuator::Declaration declared,
                                    const MeasuredActuator& measured) {
    if (measured.spin_up_s) {
        declared.spin_up_s = *measured.spin_up_s;
    }
    if (measured.spin_down_s) {
        declared.spin_down_s = *measured.spin_down_s;
    }
    if (measured.resonance_hz) {
        declared.resonance_hz = *measured.resonance_hz;
    }
    if (measured.q) {
        declared.q = *measured.q;
    }
    if (measured.resonance_hz && measured.q) {
        // Measured on this board, they are known as well as calibrate measures, not a
        // datasheet's spread (the rule bench/calibrated_feel plays too).
        declared = actuator::calibration::with_measured_margins(declared);
    }
    return declared;
}

std::string measured_source(const MeasuredActuator& measured) {
    return "measured " + measured.measured_at;
}

void use_measured_actuator(DaemonConfig& config) {
    config.actuator_source = config.actuator ? "declared" : "";
    if (!config.actuator || config.store.empty()) {
        return;
    }
    const auto file = config.store / kCalibrationStateFile;
    const auto measured = load_measured(file);
    if (!measured) {
        return;
    }
    if (measured->kind != config.actuator->kind) {
        log::warning("calibration: " + file.string() + " measured an " +
                     (measured->kind == Kind::erm ? "erm" : "lra") +
                     ", but [actuator] declares another kind; using the declaration (run "
                     "vibscore calibrate --apply again for this actuator)");
        return;
    }
    config.actuator = with_measured(*config.actuator, *measured);
    if (config.device_clefs.fit_to) {
        config.device_clefs.fit_to = config.actuator;
    }
    config.actuator_source = measured_source(*measured);
    log::info("actuator: using the numbers " + config.actuator_source + " (" + file.string() +
              "): " + actuator::describe(*config.actuator));
}

std::string iso_utc_now() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace vibscore::daemon
