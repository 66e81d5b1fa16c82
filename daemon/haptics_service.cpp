#include "daemon/haptics_service.hpp"

#include <algorithm>

#include "common/monotonic_clock.hpp"
#include "common/number_text.hpp"
#include "config.h"
#include "daemon/log.hpp"
#include "daemon/play_request.hpp"
#include "daemon/request_error.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/name_owner_watch.hpp"
#include "dbus/sdbus_compat.hpp"
#include "score/document_error.hpp"

namespace vibscore::daemon {

namespace {

using namespace haptics1::errors;

const char* error_name(RegistryError::Code code) {
    switch (code) {
        case RegistryError::Code::invalid_document:
            return kInvalidDocument;
        case RegistryError::Code::not_found:
            return kNotFound;
        case RegistryError::Code::permission_denied:
            return kPermissionDenied;
        case RegistryError::Code::limit_exceeded:
            return kLimitExceeded;
        case RegistryError::Code::in_use:
            return kBusy;
    }
    return kInvalidDocument;
}

const char* error_name(RequestError::Code code) {
    switch (code) {
        case RequestError::Code::invalid:
            return kInvalidDocument;
        case RequestError::Code::not_found:
            return kNotFound;
        case RequestError::Code::permission_denied:
            return kPermissionDenied;
        case RequestError::Code::limit_exceeded:
            return kLimitExceeded;
    }
    return kInvalidDocument;
}

// Runs a method body; whatever it throws leaves as a named D-Bus error.
template <typename Body>
auto guarded(const char* method, Body&& body) -> decltype(body()) {
    try {
        return body();
    } catch (const sdbus::Error&) {
        throw;
    } catch (const RequestError& error) {
        throw dbus::bus_error(error_name(error.code()), error.what());
    } catch (const RegistryError& error) {
        throw dbus::bus_error(error_name(error.code()), error.what());
    } catch (const DocumentError& error) {
        throw dbus::bus_error(kInvalidDocument, error.what());
    } catch (const PlayerBusy& error) {
        throw dbus::bus_error(kBusy, error.what());
    } catch (const drivers::DeviceError& error) {
        throw dbus::bus_error(kDevice, error.what());
    } catch (const std::exception& error) {
        log::error(std::string(method) + " failed unexpectedly: " + error.what());
        throw dbus::bus_error(kFailed, std::string(method) + " failed: " + error.what());
    }
}

DocumentKind kind_named(const std::string& kind) {
    const auto parsed = parse_document_kind(kind);
    if (!parsed) {
        throw RequestError(RequestError::Code::invalid,
                           "unknown kind \"" + kind + "\" (expected score or clef)");
    }
    return *parsed;
}

}  // namespace

HapticsService::HapticsService(sdbus::IConnection& connection, const DaemonConfig& config,
                               Registry& registry, PlaybackThread& playback,
                               CallerDirectory& callers, ActuatorHost& host,
                               const Authorizer& authorizer)
    : AdaptorInterfaces(connection, dbus::object_path(haptics1::kObjectPath)),
      config_(config),
      registry_(registry),
      playback_(playback),
      callers_(callers),
      host_(host),
      authorizer_(authorizer),
      announced_driver_(Driver()),
      announced_capabilities_(Capabilities()) {
    vanish_watch_ = dbus::watch_connections_leaving(connection, [this](const std::string& name) {
        playback_.call([&](Player& player) { player.sender_vanished(name); });
        callers_.forget(name);
    });
    playback_.set_listener(this);
    // A switch happens on the playback thread; the bus hears of it on the bus thread.
    host_.on_change([this] { playback_.to_bus([this] { driver_switched(); }); });
    registerAdaptor();
}

HapticsService::~HapticsService() {
    unregisterAdaptor();
    host_.on_change(nullptr);
    playback_.set_listener(nullptr);
}

std::string HapticsService::Driver() {
    return playback_.call([&](Player&) { return host_.driver(); });
}

std::vector<std::string> HapticsService::Capabilities() {
    return playback_.call([&](Player&) { return host_.capabilities().names(); });
}

double HapticsService::Intensity() {
    return playback_.call([](Player& player) { return player.master_intensity(); });
}

void HapticsService::driver_switched() {
    auto driver = Driver();
    auto capabilities = Capabilities();
    if (driver == announced_driver_ && capabilities == announced_capabilities_) {
        return;
    }
    announced_driver_ = std::move(driver);
    announced_capabilities_ = std::move(capabilities);
    dbus::emit_properties_changed(getObject(), INTERFACE_NAME, {"Driver", "Capabilities"});
}

const Caller& HapticsService::admit_caller() {
    const Caller& caller = dbus::with_current_message(
        getObject(),
        [&](const sdbus::Message& message) -> const Caller& { return callers_.identify(message); });
    if (!callers_.admit(caller.sender, monotonic_now_us())) {
        throw RequestError(RequestError::Code::limit_exceeded,
                           "too many requests from " + caller.sender + "; the limit is " +
                               number_text(callers_.requests_per_second()) + " per second");
    }
    return caller;
}

std::uint64_t HapticsService::Play(const std::string& score,
                                   const std::map<std::string, sdbus::Variant>& options) {
    return guarded("Play", [&] {
        const Caller& caller = admit_caller();
        const PlayOptions play_options = parse_play_options(options);
        if (needs_urgent_usage(play_options.usage)) {
            authorizer_.require(caller, Action::urgent_usage,
                                "Playing with usage " + std::string(to_string(play_options.usage)));
        }
        // A request that would be refused is refused before its score is read or rendered.
        playback_.call([&](Player& player) {
            player.check_admission(play_options.usage, play_options.repeat);
        });
        PlaybackRequest request = make_playback_request(
            find_score_to_play(registry_, score, play_options, config_.device_clefs), play_options,
            config_.separation_ms / 1000.0);
        request.owner = caller.uid;
        request.sender = caller.sender;
        const auto label = request.label;
        const auto id =
            playback_.call([&](Player& player) { return player.play(std::move(request)); });
        log::debug("playback " + std::to_string(id) + ": " + label + " (" +
                   std::string(to_string(play_options.usage)) + ") for uid " +
                   std::to_string(caller.uid));
        return id;
    });
}

void HapticsService::Stop(const std::uint64_t& playback_id) {
    guarded("Stop", [&] {
        const Caller& caller = admit_caller();
        const auto stop_as = [&](bool privileged) {
            return playback_.call(
                [&](Player& player) { return player.stop(playback_id, caller.uid, privileged); });
        };
        auto result = stop_as(false);
        // Only a stop that would be refused asks polkit: a caller's own playbacks need no action.
        if (result == Player::StopResult::not_permitted &&
            authorizer_.allowed(caller, Action::manage)) {
            result = stop_as(true);
        }
        switch (result) {
            case Player::StopResult::stopped:
            case Player::StopResult::not_playing:
                return;
            case Player::StopResult::not_found:
                throw RequestError(RequestError::Code::not_found,
                                   "no playback " + std::to_string(playback_id) + " was started");
            case Player::StopResult::not_permitted:
                throw RequestError(
                    RequestError::Code::permission_denied,
                    "playback " + std::to_string(playback_id) +
                        " belongs to another user; stopping it needs org.vibscore.manage");
        }
    });
}

void HapticsService::Compose(const std::string& name, const std::string& document) {
    guarded("Compose", [&] {
        const Caller& caller = admit_caller();
        authorizer_.require(caller, Action::compose, "Compose");
        const auto stored = registry_.compose(name, document);
        log::info("uid " + std::to_string(caller.uid) + " composed " +
                  std::string(to_string(stored)) + " \"" + name + "\"");
        emitRegistryChanged(std::string(to_string(stored)), name);
    });
}

void HapticsService::Delete(const std::string& kind, const std::string& name) {
    guarded("Delete", [&] {
        const Caller& caller = admit_caller();
        authorizer_.require(caller, Action::compose, "Delete");
        const auto which = kind_named(kind);
        registry_.remove(which, name);
        log::info("uid " + std::to_string(caller.uid) + " deleted " +
                  std::string(to_string(which)) + " \"" + name + "\"");
        emitRegistryChanged(std::string(to_string(which)), name);
    });
}

std::vector<sdbus::Struct<std::string, std::string>> HapticsService::List(const std::string& kind) {
    return guarded("List", [&] {
        admit_caller();
        std::vector<sdbus::Struct<std::string, std::string>> entries;
        for (const auto& entry : registry_.list(kind_named(kind))) {
            entries.emplace_back(entry.name, entry.title);
        }
        return entries;
    });
}

std::string HapticsService::Get(const std::string& kind, const std::string& name) {
    return guarded("Get", [&] {
        admit_caller();
        return registry_.get(kind_named(kind), name);
    });
}

std::string HapticsService::Origin(const std::string& kind, const std::string& name) {
    return guarded("Origin", [&] {
        admit_caller();
        return std::string(to_string(registry_.origin(kind_named(kind), name)));
    });
}

std::vector<sdbus::Struct<std::string, std::string>> HapticsService::BarClefs(
    const std::string& score) {
    return guarded("BarClefs", [&] {
        admit_caller();
        std::vector<sdbus::Struct<std::string, std::string>> bars;
        for (auto& bar : bar_clefs(find_score_to_play(registry_, score, PlayOptions{}).bundle,
                                   config_.device_clefs)) {
            bars.emplace_back(std::move(bar.written), std::move(bar.device));
        }
        return bars;
    });
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

void HapticsService::SwitchDriver(const std::string& driver) {
    guarded("SwitchDriver", [&] {
        const Caller& caller = admit_caller();
        authorizer_.require(caller, Action::manage, "Switching the driver");
        const auto known = host_.drivers();
        if (std::none_of(known.begin(), known.end(),
                         [&](const drivers::DriverInfo& info) { return info.name == driver; })) {
            std::string names;
            for (const auto& info : known) {
                names += (names.empty() ? "" : ", ") + info.name;
            }
            throw RequestError(RequestError::Code::not_found,
                               "no driver \"" + driver + "\" (available: " + names + ")");
        }
        log::info("uid " + std::to_string(caller.uid) + " switches the driver to " + driver);
        try {
            playback_.call([&](Player&) { host_.switch_to(driver); });
        } catch (const std::invalid_argument& error) {
            throw RequestError(RequestError::Code::invalid, error.what());
        }
    });
}

void HapticsService::Intensity(const double& value) {
    guarded("Intensity", [&] {
        const Caller& caller = admit_caller();
        authorizer_.require(caller, Action::manage, "Setting Intensity");
        if (!(value >= 0.0 && value <= 1.0)) {
            throw RequestError(RequestError::Code::invalid,
                               "Intensity " + number_text(value) + " is outside 0..1");
        }
        playback_.call([&](Player& player) { player.set_master_intensity(value); });
        log::info("uid " + std::to_string(caller.uid) + " set Intensity to " + number_text(value));
    });
}

std::string HapticsService::Version() {
    return VIBSCORE_VERSION;
}

void HapticsService::playback_started(std::uint64_t id, const std::string& label) {
    emitPlaybackStarted(id, label);
}

void HapticsService::playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) {
    emitPlaybackPosition(id, static_cast<std::uint32_t>(bar), static_cast<std::uint32_t>(symbol));
}

void HapticsService::playback_finished(std::uint64_t id, const std::string& reason) {
    log::debug("playback " + std::to_string(id) + " finished: " + reason);
    emitPlaybackFinished(id, reason);
}

}  // namespace vibscore::daemon
