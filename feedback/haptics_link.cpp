#include "feedback/haptics_link.hpp"

#include "common/log.hpp"
#include "common/quoted_text.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/name_owner_watch.hpp"
#include "dbus/sdbus_compat.hpp"
#include "score/clef_xml.hpp"

namespace vibscore::feedback {

HapticsLink::HapticsLink(sdbus::IConnection& system_bus, Callbacks callbacks)
    : ProxyInterfaces(system_bus, dbus::service_name(haptics1::kBusName),
                      dbus::object_path(haptics1::kObjectPath)),
      callbacks_(std::move(callbacks)) {
    owner_watch_ = dbus::watch_name_owner(system_bus, haptics1::kBusName,
                                          [this](const dbus::NameOwnerChange& change) {
                                              if (change.new_owner.empty()) {
                                                  pattern_clef_.reset();
                                                  callbacks_.service_gone();
                                              }
                                          });
    registerProxy();
}

HapticsLink::~HapticsLink() {
    unregisterProxy();
}

const Clef& HapticsLink::pattern_clef() {
    if (!pattern_clef_) {
        pattern_clef_ = read_clef(Get("clef", kPatternClef), kPatternClefHref);
    }
    return *pattern_clef_;
}

Haptics::Played HapticsLink::play(const PlayRequest& request) {
    const std::string title = quoted_text(request.title);
    try {
        const auto play = score_play(request, [this]() -> const Clef& { return pattern_clef(); });
        if (!play) {
            return {};
        }
        std::map<std::string, sdbus::Variant> options{
            {"usage", sdbus::Variant(play->usage)},
            {"repeat", sdbus::Variant(static_cast<std::int32_t>(play->repeat))},
            {"intensity", sdbus::Variant(play->intensity)},
        };
        if (!play->clef.empty()) {
            options.emplace("clef", sdbus::Variant(play->clef));
        }
        return {Play(play->score, options), false};
    } catch (const sdbus::Error& error) {
        // Busy: a more important playback holds the actuator, as feedbackd's busy vibra.
        if (error.getName() == haptics1::errors::kBusy) {
            log::debug("vibscored is busy: " + error.getMessage());
        } else {
            log::warning("vibscored did not play " + title + ": " + error.getName() + ": " +
                         error.getMessage());
        }
        return {0, error.getName() == haptics1::errors::kNotFound && !request.entry.score.empty()};
    } catch (const std::exception& error) {
        log::warning("cannot play " + title + ": " + error.what());
    }
    return {};
}

bool HapticsLink::stop(std::uint64_t playback) {
    try {
        Stop(playback);
        return true;
    } catch (const sdbus::Error& error) {
        log::warning("vibscored did not stop playback " + std::to_string(playback) + ": " +
                     error.getName() + ": " + error.getMessage());
    }
    return false;
}

void HapticsLink::onPlaybackFinished(const std::uint64_t& playback, const std::string& reason) {
    callbacks_.playback_finished(playback, reason);
}

void HapticsLink::onRegistryChanged(const std::string& kind, const std::string& name) {
    if (kind == "clef" && name == kPatternClef) {
        pattern_clef_.reset();
    }
}

}  // namespace vibscore::feedback
