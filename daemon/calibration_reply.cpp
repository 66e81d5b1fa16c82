#include "daemon/calibration_reply.hpp"

#include <sstream>
#include <vector>

#include "actuator/calibration.hpp"
#include "daemon/player.hpp"
#include "daemon/request_error.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

namespace cal = actuator::calibration;

CalibrateOptions parse_calibrate_options(const std::map<std::string, sdbus::Variant>& options) {
    CalibrateOptions parsed;
    for (const auto& [key, value] : options) {
        bool* flag = key == "apply"       ? &parsed.apply
                     : key == "recording" ? &parsed.recording
                                          : nullptr;
        if (flag == nullptr) {
            throw RequestError(RequestError::Code::invalid, "unknown Calibrate option \"" + key +
                                                                "\" (expected apply or "
                                                                "recording)");
        }
        if (dbus::variant_signature(value) != "b") {
            throw RequestError(RequestError::Code::invalid, "Calibrate option \"" + key +
                                                                "\" must be a boolean (b), not " +
                                                                dbus::variant_signature(value));
        }
        *flag = value.get<bool>();
    }
    return parsed;
}

CalibrationReply calibration_reply(const CalibrationOutcome& outcome, bool recording) {
    const auto& estimate = outcome.estimate;
    CalibrationReply reply;
    reply["kind"] =
        sdbus::Variant(std::string(estimate.kind == actuator::Kind::erm ? "erm" : "lra"));
    const auto number = [&](const char* key, const std::optional<double>& value, double scale) {
        if (value) {
            reply[key] = sdbus::Variant(*value * scale);
        }
    };
    number("spin-up-ms", estimate.spin_up_s, 1000.0);
    number("spin-down-ms", estimate.spin_down_s, 1000.0);
    number("resonance-hz", estimate.resonance_hz, 1.0);
    number("q", estimate.q, 1.0);
    number("full-scale-accel", estimate.full_scale_accel, 1.0);
    // How sure each number is travels with it: the client prints it as the offline path does.
    number("spin-up-uncertainty", estimate.spin_up_uncertainty, 1.0);
    number("spin-down-uncertainty", estimate.spin_down_uncertainty, 1.0);
    number("resonance-uncertainty", estimate.resonance_uncertainty, 1.0);
    number("q-uncertainty", estimate.q_uncertainty, 1.0);
    reply["sample-rate-hz"] = sdbus::Variant(estimate.sample_rate_hz);
    reply["residual"] = sdbus::Variant(estimate.residual);
    reply["snr-db"] = sdbus::Variant(estimate.snr_db);
    reply["trusted"] = sdbus::Variant(estimate.trusted);
    reply["problems"] = sdbus::Variant(estimate.problems);
    reply["unmeasured"] = sdbus::Variant(estimate.unmeasured);
    reply["lines"] = sdbus::Variant(cal::declaration_lines(estimate));
    std::map<std::string, std::string> declared;
    if (outcome.declared) {
        for (auto& [key, value] : actuator::to_settings(*outcome.declared)) {
            declared.emplace(std::move(key), std::move(value));
        }
    }
    reply["declared"] = sdbus::Variant(declared);
    reply["declared-source"] = sdbus::Variant(outcome.declared_source);
    reply["applied"] = sdbus::Variant(outcome.applied);
    reply["source"] = sdbus::Variant(outcome.source);
    reply["accelerometer"] = sdbus::Variant(outcome.accelerometer);
    if (recording) {
        reply["plan"] = sdbus::Variant(cal::plan_csv(outcome.plan));
        std::ostringstream samples;
        samples.precision(9);
        samples << "t,x,y,z\n";
        for (const auto& sample : outcome.samples) {
            samples << sample.t_s << "," << sample.x << "," << sample.y << "," << sample.z << "\n";
        }
        reply["recording"] = sdbus::Variant(samples.str());
    }
    return reply;
}

void throw_calibration_error(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const CalibrationRefused& refused) {
        switch (refused.why()) {
            case CalibrationRefused::Why::no_accelerometer:
                throw dbus::bus_error(haptics1::errors::kNoAccelerometer, refused.what());
            case CalibrationRefused::Why::untrusted:
                throw dbus::bus_error(haptics1::errors::kUntrusted, refused.what());
            case CalibrationRefused::Why::interrupted:
                throw dbus::bus_error(haptics1::errors::kBusy, refused.what());
        }
        throw;
    } catch (const PlayerBusy&) {
        throw;  // Busy, by the bus boundary
    } catch (const PlaybackStuck&) {
        throw;  // Device, by the bus boundary
    } catch (const drivers::DeviceError&) {
        throw;
    } catch (const RequestError&) {
        throw;
    } catch (const std::invalid_argument& invalid) {
        throw RequestError(RequestError::Code::invalid, invalid.what());
    } catch (const sdbus::Error&) {
        throw;
    } catch (const std::runtime_error& failed) {
        if (dynamic_cast<const std::system_error*>(&failed) != nullptr) {
            throw;  // the state file could not be written: Failed, logged, names the path
        }
        throw dbus::bus_error(haptics1::errors::kDevice,
                              std::string("the accelerometer failed: ") + failed.what());
    }
}

}  // namespace vibscore::daemon
