#include "client/calibrate_live.hpp"

#include <sdbus-c++/sdbus-c++.h>

#include <chrono>
#include <map>
#include <stdexcept>

#include "client/editor/daemon_errors.hpp"
#include "client/offline_verbs.hpp"
#include "client/pictures/picture_file.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"

namespace vibscore::client {

namespace cal = actuator::calibration;

namespace {

using Result = std::map<std::string, sdbus::Variant>;

// Longer than the probe (at most 6 s), the ring-down after it and the estimate: the daemon
// answers when the measurement is done.
constexpr auto kCalibrateTimeout = std::chrono::seconds(60);

template <typename T>
std::optional<T> field(const Result& result, const char* key) {
    const auto found = result.find(key);
    if (found == result.end()) {
        return std::nullopt;
    }
    return found->second.get<T>();
}

// The estimate as Calibrate's reply gives it (dbus/org.vibscore.Haptics1.xml).
cal::Estimate estimate_of(const Result& result) {
    cal::Estimate estimate;
    estimate.kind = field<std::string>(result, "kind").value_or("lra") == "erm"
                        ? actuator::Kind::erm
                        : actuator::Kind::lra;
    const auto ms = [&](const char* key) -> std::optional<double> {
        const auto value = field<double>(result, key);
        return value ? std::optional(*value / 1000.0) : std::nullopt;
    };
    estimate.spin_up_s = ms("spin-up-ms");
    estimate.spin_down_s = ms("spin-down-ms");
    estimate.resonance_hz = field<double>(result, "resonance-hz");
    estimate.q = field<double>(result, "q");
    estimate.full_scale_accel = field<double>(result, "full-scale-accel");
    estimate.spin_up_uncertainty = field<double>(result, "spin-up-uncertainty");
    estimate.spin_down_uncertainty = field<double>(result, "spin-down-uncertainty");
    estimate.resonance_uncertainty = field<double>(result, "resonance-uncertainty");
    estimate.q_uncertainty = field<double>(result, "q-uncertainty");
    estimate.sample_rate_hz = field<double>(result, "sample-rate-hz").value_or(0.0);
    estimate.residual = field<double>(result, "residual").value_or(1.0);
    estimate.snr_db = field<double>(result, "snr-db").value_or(0.0);
    estimate.trusted = field<bool>(result, "trusted").value_or(false);
    estimate.problems =
        field<std::vector<std::string>>(result, "problems").value_or(std::vector<std::string>{});
    estimate.unmeasured =
        field<std::vector<std::string>>(result, "unmeasured").value_or(std::vector<std::string>{});
    return estimate;
}

std::optional<actuator::Declaration> declared_of(const Result& result) {
    const auto settings = field<std::map<std::string, std::string>>(result, "declared");
    if (!settings || settings->empty()) {
        return std::nullopt;
    }
    std::vector<actuator::Setting> lines;
    for (const auto& [key, value] : *settings) {
        lines.push_back({key, value, "Calibrate's reply"});
    }
    return actuator::parse_declaration(lines, "Calibrate's reply");
}

}  // namespace

int calibrate_live(const CalibrateRequest& request, std::ostream& out, std::ostream& err) {
    if (!request.kind.empty() || !request.actuator_file.empty() || !request.output.empty()) {
        err << "vibscore: calibrate: --kind, --actuator and -o go with --plan or --estimate; "
               "live, vibscored probes the actuator it declares\n";
        return exit_usage;
    }
    if (const int refused = check_picture_names(request, err)) {
        return refused;
    }
    Result result;
    try {
        auto connection = sdbus::createSystemBusConnection();
        auto proxy = dbus::create_proxy(*connection, haptics1::kBusName, haptics1::kObjectPath);
        std::map<std::string, sdbus::Variant> options;
        options["apply"] = sdbus::Variant(request.apply);
        options["recording"] = sdbus::Variant(!request.png.empty() || !request.svg.empty());
        proxy->callMethod("Calibrate")
            .onInterface(haptics1::kInterface)
            .withTimeout(kCalibrateTimeout)
            .withArguments(options)
            .storeResultsTo(result);
    } catch (const sdbus::Error& error) {
        err << "vibscore: calibrate: "
            << describe_daemon_error(dbus::error_name(error), error.getMessage()) << "\n";
        return exit_failed;
    }
    try {
        const auto estimate = estimate_of(result);
        const auto declared = declared_of(result);
        if (const auto sensor = field<std::string>(result, "accelerometer")) {
            out << "# accelerometer: " << *sensor << "\n";
        }
        // Numbers an earlier calibration measured are "in use", not declared.
        const auto before = field<std::string>(result, "declared-source").value_or("declared");
        print_estimate(estimate, declared, out, err,
                       before.starts_with("measured") ? "in use (" + before + ")" : "declared");
        const bool applied = field<bool>(result, "applied").value_or(false);
        if (const auto source = field<std::string>(result, "source")) {
            out << "# in use: " << *source << (applied ? " (applied now)" : "") << "\n";
        }
        if (estimate.trusted && !request.apply) {
            err << "vibscore: calibrate: trusted; vibscore calibrate --apply makes these the "
                   "numbers in use\n";
        }
        const auto plan_text = field<std::string>(result, "plan");
        const auto recording = field<std::string>(result, "recording");
        if (plan_text && recording) {
            const auto plan = cal::parse_plan_csv(*plan_text, "Calibrate's plan", estimate.kind);
            const auto samples = cal::parse_samples_csv(*recording, "Calibrate's recording");
            for (const auto& path : {request.png, request.svg}) {
                if (!path.empty()) {
                    write_calibration_picture(path, plan, samples, estimate, declared);
                }
            }
        }
        return estimate.trusted && (applied || !request.apply) ? exit_ok : exit_failed;
    } catch (const std::exception& error) {
        err << "vibscore: calibrate: " << error.what() << "\n";
        return exit_failed;
    }
}

}  // namespace vibscore::client
