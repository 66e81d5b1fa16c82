#include "daemon/haptics_service.hpp"

#include <algorithm>

#include <cmath>

#include "config.h"
#include "daemon/event_loop.hpp"
#include "daemon/log.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "score/document_error.hpp"

namespace vibscore::daemon {

namespace {

constexpr const char* kInvalid = "org.vibscore.Haptics1.Error.InvalidDocument";
constexpr const char* kNotFound = "org.vibscore.Haptics1.Error.NotFound";
constexpr const char* kPermission = "org.vibscore.Haptics1.Error.PermissionDenied";
constexpr const char* kLimit = "org.vibscore.Haptics1.Error.LimitExceeded";
constexpr const char* kBusy = "org.vibscore.Haptics1.Error.Busy";
constexpr const char* kDevice = "org.vibscore.Haptics1.Error.Device";

// A playback's cues are kept in memory; this bounds that memory for one hour of dense shapes.
constexpr std::size_t kMaxCues = 2'000'000;

const char* error_name(RegistryError::Code code) {
    switch (code) {
        case RegistryError::Code::invalid_document:
            return kInvalid;
        case RegistryError::Code::not_found:
            return kNotFound;
        case RegistryError::Code::permission_denied:
            return kPermission;
        case RegistryError::Code::limit_exceeded:
            return kLimit;
        case RegistryError::Code::in_use:
            return kBusy;
    }
    return kInvalid;
}

// Runs a method body; whatever it throws leaves as a named D-Bus error.
template <typename Body>
auto guarded(const char* method, Body&& body) -> decltype(body()) {
    try {
        return body();
    } catch (const sdbus::Error&) {
        throw;
    } catch (const RegistryError& error) {
        throw sdbus::Error(error_name(error.code()), error.what());
    } catch (const DocumentError& error) {
        throw sdbus::Error(kInvalid, error.what());
    } catch (const PlayerBusy& error) {
        throw sdbus::Error(kBusy, error.what());
    } catch (const drivers::DeviceError& error) {
        throw sdbus::Error(kDevice, error.what());
    } catch (const std::exception& error) {
        log::error(std::string(method) + " failed unexpectedly: " + error.what());
        throw sdbus::Error("org.freedesktop.DBus.Error.Failed",
                           std::string(method) + " failed: " + error.what());
    }
}

DocumentKind document_class(const std::string& kind) {
    const auto parsed = parse_document_kind(kind);
    if (!parsed) {
        throw sdbus::Error(kInvalid, "unknown kind \"" + kind + "\" (expected score or clef)");
    }
    return *parsed;
}

template <typename T>
T option_value(const std::string& key, const sdbus::Variant& value, const char* signature,
               const char* type_name) {
    if (value.peekValueType() != signature) {
        throw sdbus::Error(kInvalid, "option \"" + key + "\" must be " + type_name + " (" +
                                         signature + "), not " + value.peekValueType());
    }
    return value.get<T>();
}

bool is_inline_document(const std::string& score) {
    const auto first = score.find_first_not_of(" \t\r\n");
    return first != std::string::npos && score[first] == '<';
}

}  // namespace

HapticsService::HapticsService(sdbus::IConnection& connection, Registry& registry, Player& player,
                               CallerDirectory& callers, DriverControl& driver_control,
                               Settings settings)
    : AdaptorInterfaces(connection, kObjectPath),
      registry_(registry),
      player_(player),
      callers_(callers),
      driver_control_(driver_control),
      settings_(std::move(settings)) {
    registerAdaptor();
}

void HapticsService::update_settings(Settings settings) {
    const bool changed =
        settings.driver != settings_.driver || settings.capabilities != settings_.capabilities;
    settings_ = std::move(settings);
    if (changed) {
        getObject().emitPropertiesChangedSignal(INTERFACE_NAME, {"Driver", "Capabilities"});
    }
}

HapticsService::~HapticsService() {
    unregisterAdaptor();
}

const Caller& HapticsService::admit_caller() {
    const auto* message = getObject().getCurrentlyProcessedMessage();
    const Caller& caller = callers_.identify(*message);
    if (!callers_.admit(caller.sender, monotonic_now_us())) {
        throw sdbus::Error(kLimit, "too many requests from " + caller.sender + "; the limit is " +
                                       std::to_string(callers_.requests_per_second()) +
                                       " per second");
    }
    return caller;
}

void HapticsService::require_privileged(const Caller& caller, const char* action) const {
    if (!caller.privileged) {
        throw sdbus::Error(kPermission, std::string(action) +
                                            " needs root or membership of "
                                            "group vibscore (caller uid " +
                                            std::to_string(caller.uid) + ")");
    }
}

PlaybackRequest HapticsService::prepare(const std::string& score,
                                        const std::map<std::string, sdbus::Variant>& options,
                                        const Caller& caller) const {
    PlaybackRequest request;
    request.owner = caller.uid;
    request.sender = caller.sender;
    std::string clef_override;
    std::uint32_t start_bar = 0;
    for (const auto& [key, value] : options) {
        if (key == "usage") {
            const auto name = option_value<std::string>(key, value, "s", "a string");
            const auto usage = parse_usage(name);
            if (!usage) {
                throw sdbus::Error(kInvalid, "unknown usage \"" + name + "\" (expected " +
                                                 std::string(usage_names()) + ")");
            }
            request.usage = *usage;
        } else if (key == "repeat") {
            request.repeat = option_value<std::int32_t>(key, value, "i", "an int32");
            if (request.repeat < -1) {
                throw sdbus::Error(kInvalid, "repeat " + std::to_string(request.repeat) +
                                                 " is invalid (0 once, n more times, -1 forever)");
            }
        } else if (key == "intensity") {
            request.intensity = option_value<double>(key, value, "d", "a double");
            if (!(request.intensity >= 0.0 && request.intensity <= 1.0)) {
                throw sdbus::Error(kInvalid, "intensity " + std::to_string(request.intensity) +
                                                 " is outside 0..1");
            }
        } else if (key == "clef") {
            clef_override = option_value<std::string>(key, value, "s", "a string");
        } else if (key == "start-bar") {
            start_bar = option_value<std::uint32_t>(key, value, "u", "a uint32");
        } else {
            throw sdbus::Error(kInvalid, "unknown option \"" + key +
                                             "\" (expected usage, repeat, intensity, clef, "
                                             "start-bar)");
        }
    }

    ScoreBundle bundle;
    if (is_inline_document(score)) {
        bundle = registry_.inline_score(score);
        request.label = "<inline>";
    } else {
        bundle = registry_.score(score);
        request.label = score;
    }
    if (!clef_override.empty()) {
        registry_.clef(clef_override);  // NotFound before anything else
        bundle = bind_clefs(ParsedScore{bundle.score, bundle.where}, bundle.file,
                            [&](const ClefDeclaration&, const SourceLocation&) {
                                return registry_.clef(clef_override);
                            });
    }
    if (start_bar >= bundle.score.bars.size()) {
        throw sdbus::Error(kInvalid, "start-bar " + std::to_string(start_bar) +
                                         " is past the last bar (the score has " +
                                         std::to_string(bundle.score.bars.size()) + ")");
    }
    render::RenderOptions render_options;
    render_options.separation_s = settings_.separation_s;
    render_options.start_bar = start_bar;
    const render::Performance performance(bundle, render_options);
    request.cues = render::cue_schedule(performance);
    if (request.cues.size() > kMaxCues) {
        throw sdbus::Error(kLimit, "the score needs " + std::to_string(request.cues.size()) +
                                       " actuator commands; the limit is " +
                                       std::to_string(kMaxCues));
    }
    request.duration_s = performance.duration();
    return request;
}

std::uint64_t HapticsService::Play(const std::string& score,
                                   const std::map<std::string, sdbus::Variant>& options) {
    return guarded("Play", [&] {
        const Caller& caller = admit_caller();
        auto request = prepare(score, options, caller);
        const auto label = request.label;
        const auto usage = request.usage;
        const auto id = player_.play(std::move(request));
        log::debug("playback " + std::to_string(id) + ": " + label + " (" +
                   std::string(to_string(usage)) + ") for uid " + std::to_string(caller.uid));
        return id;
    });
}

void HapticsService::Stop(const std::uint64_t& playback_id) {
    guarded("Stop", [&] {
        const Caller& caller = admit_caller();
        switch (player_.stop(playback_id, caller.uid, caller.privileged)) {
            case Player::StopResult::stopped:
            case Player::StopResult::not_playing:
                return;
            case Player::StopResult::not_found:
                throw sdbus::Error(kNotFound,
                                   "no playback " + std::to_string(playback_id) + " was started");
            case Player::StopResult::not_permitted:
                throw sdbus::Error(kPermission, "playback " + std::to_string(playback_id) +
                                                    " belongs to another user");
        }
    });
}

void HapticsService::Compose(const std::string& name, const std::string& document) {
    guarded("Compose", [&] {
        const Caller& caller = admit_caller();
        require_privileged(caller, "Compose");
        const auto stored = registry_.compose(name, document);
        log::info("uid " + std::to_string(caller.uid) + " composed " +
                  std::string(to_string(stored)) + " \"" + name + "\"");
        emitRegistryChanged(std::string(to_string(stored)), name);
    });
}

void HapticsService::Delete(const std::string& kind, const std::string& name) {
    guarded("Delete", [&] {
        const Caller& caller = admit_caller();
        require_privileged(caller, "Delete");
        const auto which = document_class(kind);
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
        for (const auto& entry : registry_.list(document_class(kind))) {
            entries.emplace_back(entry.name, entry.title);
        }
        return entries;
    });
}

std::string HapticsService::Get(const std::string& kind, const std::string& name) {
    return guarded("Get", [&] {
        admit_caller();
        return registry_.get(document_class(kind), name);
    });
}

std::vector<sdbus::Struct<std::string, std::string>> HapticsService::ListDrivers() {
    return guarded("ListDrivers", [&] {
        admit_caller();
        std::vector<sdbus::Struct<std::string, std::string>> drivers;
        for (const auto& driver : driver_control_.drivers()) {
            drivers.emplace_back(driver.name, driver.description);
        }
        return drivers;
    });
}

void HapticsService::SwitchDriver(const std::string& driver) {
    guarded("SwitchDriver", [&] {
        const Caller& caller = admit_caller();
        require_privileged(caller, "Switching the driver");
        const auto known = driver_control_.drivers();
        if (std::none_of(known.begin(), known.end(),
                         [&](const drivers::DriverInfo& info) { return info.name == driver; })) {
            std::string names;
            for (const auto& info : known) {
                names += (names.empty() ? "" : ", ") + info.name;
            }
            throw sdbus::Error(kNotFound,
                               "no driver \"" + driver + "\" (available: " + names + ")");
        }
        log::info("uid " + std::to_string(caller.uid) + " switches the driver to " + driver);
        try {
            driver_control_.switch_driver(driver);
        } catch (const std::invalid_argument& error) {
            throw sdbus::Error(kInvalid, error.what());
        }
    });
}

void HapticsService::Intensity(const double& value) {
    guarded("Intensity", [&] {
        const Caller& caller = admit_caller();
        require_privileged(caller, "Setting Intensity");
        if (!(value >= 0.0 && value <= 1.0)) {
            throw sdbus::Error(kInvalid, "Intensity " + std::to_string(value) + " is outside 0..1");
        }
        player_.set_master_intensity(value);
        log::info("uid " + std::to_string(caller.uid) + " set Intensity to " +
                  std::to_string(value));
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
