#include "feedback/haptics_link.hpp"

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

void HapticsLink::onPlaybackFinished(const std::uint64_t& playback, const std::string& reason) {
    callbacks_.playback_finished(playback, reason);
}

void HapticsLink::onRegistryChanged(const std::string& kind, const std::string& name) {
    if (kind == "clef" && name == kPatternClef) {
        pattern_clef_.reset();
    }
}

}  // namespace vibscore::feedback
