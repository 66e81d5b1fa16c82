#include "feedback/haptics_link.hpp"

#include "dbus/haptics1_names.hpp"
#include "score/clef_xml.hpp"

namespace vibscore::feedback {

HapticsLink::HapticsLink(sdbus::IConnection& system_bus, Callbacks callbacks)
    : ProxyInterfaces(system_bus, haptics1::kBusName, haptics1::kObjectPath),
      callbacks_(std::move(callbacks)) {
    owner_watch_ = system_bus.addMatch(
        std::string("type='signal',sender='org.freedesktop.DBus',interface='org.freedesktop.DBus',"
                    "member='NameOwnerChanged',arg0='") +
            haptics1::kBusName + "'",
        [this](sdbus::Message& message) {
            std::string name, old_owner, new_owner;
            message >> name >> old_owner >> new_owner;
            if (new_owner.empty()) {
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

void HapticsLink::onPlaybackFinished(const std::uint64_t& playback, const std::string& reason) {
    callbacks_.playback_finished(playback, reason);
}

void HapticsLink::onRegistryChanged(const std::string& kind, const std::string& name) {
    if (kind == "clef" && name == kPatternClef) {
        pattern_clef_.reset();
    }
}

}  // namespace vibscore::feedback
