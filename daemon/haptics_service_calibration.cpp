#include "daemon/haptics_service.hpp"

#include "common/log.hpp"
#include "daemon/calibration_reply.hpp"
#include "daemon/request_error.hpp"
#include "dbus/sdbus_compat.hpp"

// HapticsService's calibration: Calibrate (vibscore calibrate) and the ActuatorSource property.
namespace vibscore::daemon {

std::string HapticsService::ActuatorSource() {
    return config_.actuator ? (config_.actuator_source.empty() ? std::string("declared")
                                                               : config_.actuator_source)
                            : std::string();
}

void HapticsService::Calibrate(sdbus::Result<std::map<std::string, sdbus::Variant>>&& result,
                               std::map<std::string, sdbus::Variant> options) {
    const auto reply = DeferredReply<CalibrationReply>::make(std::move(result), "Calibrate");
    reply->start([&] {
        const Caller caller = admit_caller();
        const CalibrateOptions parsed = parse_calibrate_options(options);
        authorizer_.decide(caller, Action::manage,
                           [this, reply, caller, parsed](const Decision& decision) {
                               reply->start([&] {
                                   decision.require("Calibrating the actuator");
                                   start_calibration(reply, caller, parsed);
                               });
                           });
    });
}

void HapticsService::start_calibration(
    const std::shared_ptr<DeferredReply<CalibrationReply>>& reply, const Caller& caller,
    const CalibrateOptions& options) {
    if (calibrator_ == nullptr) {
        throw RequestError(RequestError::Code::invalid, "this daemon cannot calibrate");
    }
    log::info("uid " + std::to_string(caller.uid) + " calibrates the actuator" +
                  (options.apply ? " (apply)" : ""),
              {{"CALLER_UID", std::to_string(caller.uid)}});
    try {
        calibrator_->start(options.apply, caller.uid, caller.sender,
                           [this, reply, options](std::optional<CalibrationOutcome> outcome,
                                                  std::exception_ptr error) {
                               if (outcome && outcome->applied) {
                                   // The numbers in use changed: compensation and clef fitting use
                                   // them now, and the Actuator property says so.
                                   republish_actuator();
                                   dbus::emit_properties_changed(getObject(), INTERFACE_NAME,
                                                                 {"Actuator", "ActuatorSource"});
                               }
                               reply->finish([&] {
                                   if (error) {
                                       throw_calibration_error(error);
                                   }
                                   return calibration_reply(*outcome, options.recording);
                               });
                           });
    } catch (...) {
        throw_calibration_error(std::current_exception());
    }
}

}  // namespace vibscore::daemon
