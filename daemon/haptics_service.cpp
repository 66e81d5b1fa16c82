#include "daemon/haptics_service.hpp"

#include <algorithm>
#include <mutex>

#include "actuator/declaration.hpp"
#include "common/log.hpp"
#include "common/monotonic_clock.hpp"
#include "common/number_text.hpp"
#include "config.h"
#include "daemon/bus_errors.hpp"
#include "daemon/calibration_reply.hpp"
#include "daemon/request_error.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/name_owner_watch.hpp"
#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

namespace {

// The properties the running backend and the declared actuator decide, read on the playback
// thread, where the host switches and the declaration changes.
void take_from_host(BusProperties& properties, const ActuatorHost& host) {
    properties.driver = host.driver();
    properties.driver_reason = host.reason();
    properties.capabilities = host.capabilities().names();
    properties.actuator.clear();
    if (const auto& declared = host.declaration()) {
        for (auto& [key, value] : actuator::to_settings(*declared)) {
            properties.actuator.emplace(std::move(key), std::move(value));
        }
    }
}

}  // namespace

HapticsService::HapticsService(sdbus::IConnection& connection, const DaemonConfig& config,
                               Registry& registry, PlaybackThread& playback,
                               CallerDirectory& callers, ActuatorHost& host, Authorizer& authorizer)
    : AdaptorInterfaces(connection, dbus::object_path(haptics1::kObjectPath)),
      config_(config),
      registry_(registry),
      playback_(playback),
      callers_(callers),
      host_(host),
      authorizer_(authorizer) {
    // The first snapshot; from here on the playback thread publishes each change itself.
    playback_.call([&playback = playback_, &host = host_](Player& player) {
        playback.publish([&](BusProperties& properties) {
            take_from_host(properties, host);
            properties.intensity = player.master_intensity();
        });
    });
    const auto properties = playback_.properties();
    announced_driver_ = properties->driver;
    announced_reason_ = properties->driver_reason;
    announced_capabilities_ = properties->capabilities;
    announced_actuator_ = properties->actuator;
    vanish_watch_ = dbus::watch_connections_leaving(connection, [this](const std::string& name) {
        callers_.forget(name);
        admission_.forget(name);
        authorizer_.forget(name);
        try {
            playback_.call([name](Player& player) { player.sender_vanished(name); });
        } catch (const PlaybackStuck& stuck) {
            log::error("could not end the playbacks of " + name + ": " + stuck.what());
        }
    });
    playback_.set_listener(this);
    // A switch or a new declaration happens on the playback thread, which publishes it; the bus
    // hears of it on the bus thread.
    host_.on_change([this] {
        playback_.publish(
            [&host = host_](BusProperties& properties) { take_from_host(properties, host); });
        playback_.to_bus([this] { driver_switched(); });
    });
    registerAdaptor();
}

HapticsService::~HapticsService() {
    *alive_ = false;
    unregisterAdaptor();
    host_.on_change(nullptr);
    playback_.set_listener(nullptr);
}

// The properties the playback thread owns are read from its last snapshot: no read waits for
// it (bus_properties.hpp).
std::string HapticsService::Driver() {
    return playback_.properties()->driver;
}

std::string HapticsService::DriverReason() {
    return playback_.properties()->driver_reason;
}

std::map<std::string, std::string> HapticsService::RegistryFolders() {
    return {{"shipped", config_.shipped.string()}, {"store", config_.store.string()}};
}

std::vector<std::string> HapticsService::Capabilities() {
    return playback_.properties()->capabilities;
}

std::map<std::string, std::string> HapticsService::Actuator() {
    return playback_.properties()->actuator;
}

double HapticsService::Intensity() {
    return playback_.properties()->intensity;
}

void HapticsService::driver_switched() {
    const auto properties = playback_.properties();
    const auto& driver = properties->driver;
    const auto& reason = properties->driver_reason;
    const auto& capabilities = properties->capabilities;
    const auto& actuator = properties->actuator;
    if (driver == announced_driver_ && reason == announced_reason_ &&
        capabilities == announced_capabilities_ && actuator == announced_actuator_) {
        return;
    }
    announced_driver_ = driver;
    announced_reason_ = reason;
    announced_capabilities_ = capabilities;
    announced_actuator_ = actuator;
    dbus::emit_properties_changed(getObject(), INTERFACE_NAME,
                                  {"Driver", "DriverReason", "Capabilities", "Actuator"});
}

void HapticsService::republish_actuator() {
    try {
        playback_.call([&playback = playback_, &host = host_](Player&) {
            playback.publish(
                [&host](BusProperties& properties) { take_from_host(properties, host); });
        });
    } catch (const PlaybackStuck& stuck) {
        // The snapshot follows at the next switch or reload; the signal still goes out.
        log::error("after a calibration: " + std::string(stuck.what()));
    }
    announced_actuator_ = playback_.properties()->actuator;
}

Caller HapticsService::identify_caller() {
    return dbus::with_current_message(
        getObject(),
        [&](const sdbus::Message& message) -> const Caller& { return callers_.identify(message); });
}

// The probe is the least CPU time: a document needs its budget at or above it (admission.hpp:
// a cost above 0 needs the bucket at or above it).
constexpr double kDocumentCpuProbe_s = 1e-9;

Cost HapticsService::document_cost(std::size_t bytes) {
    return {1.0, static_cast<double>(bytes), bytes > 0 ? kDocumentCpuProbe_s : 0.0};
}

Caller HapticsService::admit_caller(const Cost& cost, ChargedTo* charged_to) {
    const Caller caller = identify_caller();
    // The running configuration's budgets (a reload applies from the next request).
    AdmissionBudgets budgets = config_.admission;
    budgets.user.rate.requests = config_.requests_per_second;
    budgets.user.burst.requests = config_.request_burst;
    admission_.set_budgets(budgets);
    const auto admitted = admission_.admit(caller.uid, caller.sender, cost, monotonic_now_us());
    if (!admitted.admitted) {
        throw RequestError(RequestError::Code::limit_exceeded, admitted.refusal);
    }
    if (charged_to != nullptr) {
        *charged_to = admitted.charged_to;
    }
    return caller;
}

std::vector<sdbus::Struct<std::string, std::string>> HapticsService::ListDrivers() {
    return guarded("ListDrivers", [&] {
        admit_caller();
        std::vector<sdbus::Struct<std::string, std::string>> drivers;
        for (const auto& driver : host_.drivers()) {
            drivers.emplace_back(driver.name, driver.description);
        }
        return drivers;
    });
}

void HapticsService::SwitchDriver(sdbus::Result<>&& result, std::string driver) {
    const auto reply = DeferredReply<>::make(std::move(result), "SwitchDriver");
    reply->start([&] {
        const Caller caller = admit_caller();
        when_allowed(reply, caller, Action::manage, "Switching the driver", [this, caller, driver] {
            const auto known = host_.drivers();
            if (std::none_of(known.begin(), known.end(), [&](const drivers::DriverInfo& info) {
                    return info.name == driver;
                })) {
                std::string names;
                for (const auto& info : known) {
                    names += (names.empty() ? "" : ", ") + info.name;
                }
                throw RequestError(RequestError::Code::not_found,
                                   "no driver \"" + driver + "\" (available: " + names + ")");
            }
            log::info("uid " + std::to_string(caller.uid) + " switches the driver to " + driver,
                      {{"CALLER_UID", std::to_string(caller.uid)}});
            try {
                playback_.call([&host = host_, driver](Player&) { host.switch_to(driver); });
            } catch (const std::invalid_argument& error) {
                throw RequestError(RequestError::Code::invalid, error.what());
            }
        });
    });
}

void HapticsService::set_intensity(const Caller& caller, double value) {
    if (!(value >= 0.0 && value <= 1.0)) {
        throw RequestError(RequestError::Code::out_of_range,
                           "Intensity " + number_text(value) + " is outside 0..1");
    }
    playback_.call([value, &playback = playback_](Player& player) {
        player.set_master_intensity(value);
        playback.publish([value](BusProperties& properties) { properties.intensity = value; });
    });
    log::info("uid " + std::to_string(caller.uid) + " set Intensity to " + number_text(value),
              {{"CALLER_UID", std::to_string(caller.uid)}});
}

void HapticsService::SetIntensity(sdbus::Result<>&& result, double value) {
    const auto reply = DeferredReply<>::make(std::move(result), "SetIntensity");
    reply->start([&] {
        const Caller caller = admit_caller();
        when_allowed(reply, caller, Action::manage, "Setting Intensity",
                     [this, caller, value] { set_intensity(caller, value); });
    });
}

std::string HapticsService::Version() {
    return VIBSCORE_VERSION;
}

void HapticsService::playback_started(std::uint64_t id, const std::string& label) {
    emitPlaybackStarted(id, label);
    if (calibrator_ != nullptr) {
        calibrator_->playback_started(id);
    }
}

void HapticsService::playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) {
    emitPlaybackPosition(id, static_cast<std::uint32_t>(bar), static_cast<std::uint32_t>(symbol));
}

void HapticsService::playback_finished(std::uint64_t id, const std::string& reason) {
    log::debug("playback " + std::to_string(id) + " finished: " + reason,
               {{"PLAYBACK_ID", std::to_string(id)}, {"REASON", reason}});
    emitPlaybackFinished(id, reason);
    if (calibrator_ != nullptr) {
        calibrator_->playback_finished(id, reason);
    }
}

}  // namespace vibscore::daemon
