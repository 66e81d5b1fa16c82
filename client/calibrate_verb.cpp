#include "client/calibrate_verb.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "client/actuator_option.hpp"
#include "client/offline_verbs.hpp"
#include "client/pictures/calibration_picture.hpp"
#include "common/number_text.hpp"

namespace vibscore::client {

namespace cal = actuator::calibration;

namespace {

std::string read_text(const std::string& file) {
    std::ifstream in(file);
    if (!in) {
        throw std::runtime_error(file + ": cannot open: " + std::strerror(errno));
    }
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text(const std::string& file, const std::string& text) {
    std::ofstream out(file, std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
        throw std::runtime_error(file + ": cannot write: " + std::strerror(errno));
    }
}

// The nominal declaration (--actuator FILE) and the kind: --kind, else the file's. nullopt kind
// when neither tells it.
struct Nominal {
    std::optional<actuator::Declaration> declared;
    std::optional<actuator::Kind> kind;
};

Nominal nominal_of(const CalibrateRequest& request) {
    Nominal nominal;
    if (!request.actuator_file.empty()) {
        nominal.declared = load_actuator(request.actuator_file);
        nominal.kind = nominal.declared->kind;
    }
    if (!request.kind.empty()) {
        const auto kind = request.kind == "erm" ? actuator::Kind::erm : actuator::Kind::lra;
        if (nominal.declared && nominal.declared->kind != kind) {
            throw std::invalid_argument("--kind " + request.kind + " but " + request.actuator_file +
                                        " declares another kind");
        }
        nominal.kind = kind;
    }
    return nominal;
}

constexpr const char* kNoKind =
    "vibscore: calibrate: say which actuator to probe: --kind erm|lra, or --actuator FILE with "
    "an [actuator] section\n";

// The nominal declaration and kind of --plan and --estimate: exit_ok, or exit_usage having said
// why (a bad --actuator file, or no kind from --kind or the file).
int usable_nominal(const CalibrateRequest& request, Nominal& nominal, std::ostream& err) {
    try {
        nominal = nominal_of(request);
    } catch (const std::exception& error) {
        err << "vibscore: calibrate: " << error.what() << "\n";
        return exit_usage;
    }
    if (!nominal.kind) {
        err << kNoKind;
        return exit_usage;
    }
    return exit_ok;
}

}  // namespace

int check_picture_names(const CalibrateRequest& request, std::ostream& err) {
    try {
        for (const auto& path : {request.png, request.svg}) {
            if (!path.empty()) {
                pictures::picture_format_for(path);
            }
        }
    } catch (const std::exception& error) {
        err << "vibscore: calibrate: " << error.what() << "\n";
        return exit_usage;
    }
    return exit_ok;
}

namespace {

// "measured 168.2 Hz, declared 175 Hz" rows for the keys of the estimate's kind.
void print_beside(const cal::Estimate& estimate,
                  const std::optional<actuator::Declaration>& declared, std::ostream& out,
                  const std::string& declared_as) {
    const auto row = [&](const char* key, const std::optional<double>& measured, double scale,
                         std::optional<double> declared_value) {
        out << "# " << key << ": measured "
            << (measured ? rounded_text(*measured * scale, 4) : std::string("-"));
        if (declared_value) {
            out << ", " << declared_as << " " << rounded_text(*declared_value * scale, 4);
        }
        out << "\n";
    };
    const bool same_kind = declared && declared->kind == estimate.kind;
    if (estimate.kind == actuator::Kind::erm) {
        row("spin-up-ms", estimate.spin_up_s, 1000.0,
            same_kind ? std::optional(declared->spin_up_s) : std::nullopt);
        row("spin-down-ms", estimate.spin_down_s, 1000.0,
            same_kind ? std::optional(declared->spin_down_s) : std::nullopt);
    } else {
        row("resonance-hz", estimate.resonance_hz, 1.0,
            same_kind ? std::optional(declared->resonance_hz) : std::nullopt);
        row("q", estimate.q, 1.0, same_kind ? std::optional(declared->q) : std::nullopt);
    }
}

}  // namespace

actuator::Declaration with_measured(actuator::Declaration base, const cal::Estimate& estimate) {
    base.kind = estimate.kind;
    if (estimate.spin_up_s) {
        base.spin_up_s = *estimate.spin_up_s;
    }
    if (estimate.spin_down_s) {
        base.spin_down_s = *estimate.spin_down_s;
    }
    if (estimate.resonance_hz) {
        base.resonance_hz = *estimate.resonance_hz;
    }
    if (estimate.q) {
        base.q = *estimate.q;
    }
    return base;
}

void print_estimate(const cal::Estimate& estimate,
                    const std::optional<actuator::Declaration>& declared, std::ostream& out,
                    std::ostream& err, const std::string& declared_as) {
    out << cal::declaration_lines(estimate);
    print_beside(estimate, declared, out, declared_as);
    for (const auto& what : estimate.unmeasured) {
        err << "vibscore: calibrate: not measured: " << what << "\n";
    }
    if (!estimate.trusted) {
        err << "vibscore: calibrate: the estimate is not trusted (residual "
            << rounded_text(estimate.residual, 3) << ", signal-to-noise "
            << rounded_text(estimate.snr_db, 3) << " dB):\n";
        for (const auto& problem : estimate.problems) {
            err << "  " << problem << "\n";
        }
        if (estimate.problems.empty()) {
            err << "  (no reason given)\n";
        }
    }
}

void write_calibration_picture(const std::string& path, const cal::Plan& plan,
                               const std::vector<cal::Sample>& samples,
                               const cal::Estimate& estimate,
                               const std::optional<actuator::Declaration>& declared) {
    pictures::picture_format_for(path);
    pictures::CalibrationPicture::Traces traces;
    traces.recorded = cal::measured_magnitude(samples, plan.kind);
    const double scale = estimate.full_scale_accel.value_or(1.0);
    actuator::Declaration base;
    if (declared) {
        base = *declared;
    }
    base.kind = estimate.kind;
    const bool fitted_any = estimate.spin_up_s || estimate.spin_down_s || estimate.resonance_hz;
    if (fitted_any) {
        traces.fitted = cal::predicted_magnitude(plan, with_measured(base, estimate), scale,
                                                 traces.recorded.t_s);
    }
    if (declared && declared->kind == estimate.kind) {
        traces.declared = cal::predicted_magnitude(plan, *declared, scale, traces.recorded.t_s);
    }
    std::string measured;
    const auto add = [&](const char* what, const std::optional<double>& value, double scale,
                         const char* unit) {
        if (value) {
            measured += (measured.empty() ? "" : ", ") + std::string(what) + " " +
                        rounded_text(*value * scale, 4) + unit;
        }
    };
    add("resonance", estimate.resonance_hz, 1.0, " Hz");
    add("Q", estimate.q, 1.0, "");
    add("spin-up", estimate.spin_up_s, 1000.0, " ms");
    add("spin-down", estimate.spin_down_s, 1000.0, " ms");
    std::string caption = "measured " + (measured.empty() ? std::string("nothing") : measured) +
                          "; residual " + rounded_text(estimate.residual, 3) +
                          ", signal-to-noise " + rounded_text(estimate.snr_db, 3) + " dB, " +
                          rounded_text(estimate.sample_rate_hz, 4) + " Hz sampling; " +
                          (estimate.trusted ? "trusted" : "NOT trusted");
    const std::string title =
        std::string("calibration of the ") + (estimate.kind == actuator::Kind::erm ? "ERM" : "LRA");
    pictures::write_picture(pictures::CalibrationPicture(std::move(traces), title, caption), path);
}

int calibrate_plan(const CalibrateRequest& request, std::ostream& out, std::ostream& err) {
    Nominal nominal;
    if (const int refused = usable_nominal(request, nominal, err)) {
        return refused;
    }
    try {
        const auto plan = cal::make_plan(*nominal.kind, nominal.declared);
        const auto text = cal::plan_csv(plan);
        if (request.output.empty() || request.output == "-") {
            out << text;
        } else {
            write_text(request.output, text);
            err << "vibscore: calibrate: wrote the " << rounded_text(plan.duration_s(), 3)
                << " s probe for an " << (*nominal.kind == actuator::Kind::erm ? "ERM" : "LRA")
                << " to " << request.output
                << "; record it as t,x,y,z (seconds from its first row, m/s\u00b2) and run "
                   "vibscore calibrate --estimate "
                << request.output << " ACCEL.csv\n";
        }
        return exit_ok;
    } catch (const std::exception& error) {
        err << "vibscore: calibrate: " << error.what() << "\n";
        return exit_failed;
    }
}

int calibrate_estimate(const CalibrateRequest& request, std::ostream& out, std::ostream& err) {
    Nominal nominal;
    if (const int refused = usable_nominal(request, nominal, err)) {
        return refused;
    }
    if (request.estimate.size() != 2) {
        err << "vibscore: calibrate --estimate takes two files: PLAN.csv ACCEL.csv\n";
        return exit_usage;
    }
    if (const int refused = check_picture_names(request, err)) {
        return refused;
    }
    try {
        const auto& plan_file = request.estimate[0];
        const auto& samples_file = request.estimate[1];
        const auto plan = cal::parse_plan_csv(read_text(plan_file), plan_file, *nominal.kind);
        const auto samples = cal::parse_samples_csv(read_text(samples_file), samples_file);
        const auto estimate = cal::estimate(plan, samples, nominal.declared);
        print_estimate(estimate, nominal.declared, out, err);
        for (const auto& path : {request.png, request.svg}) {
            if (!path.empty()) {
                write_calibration_picture(path, plan, samples, estimate, nominal.declared);
            }
        }
        return estimate.trusted ? exit_ok : exit_failed;
    } catch (const std::exception& error) {
        err << "vibscore: calibrate: " << error.what() << "\n";
        return exit_failed;
    }
}

}  // namespace vibscore::client
