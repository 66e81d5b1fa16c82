#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "feedback/haptics.hpp"
#include "haptics1-proxy.h"
#include "score/clef.hpp"

namespace vibscore::feedback {

// vibscored as vibscore-feedback uses it: its public D-Bus API on the system bus, nothing more.
// It plays and stops what the event table asks (Haptics); what vibscored reports comes back
// through the callbacks, on the thread that serves the connection.
class HapticsLink : public sdbus::ProxyInterfaces<org::vibscore::Haptics1_proxy>, public Haptics {
  public:
    struct Callbacks {
        std::function<void(std::uint64_t playback, const std::string& reason)> playback_finished;
        // vibscored left the bus: none of the playbacks it had will report an end.
        std::function<void()> service_gone;
    };

    HapticsLink(sdbus::IConnection& system_bus, Callbacks callbacks);
    ~HapticsLink();
    HapticsLink(const HapticsLink&) = delete;
    HapticsLink& operator=(const HapticsLink&) = delete;

    Played play(const PlayRequest& request) override;
    bool stop(std::uint64_t playback) override;

  private:
    // The registry clef patterns are written on (kPatternClef), asked for once and kept until
    // the registry announces a change of it. Throws sdbus::Error, or DocumentError for a clef
    // that does not read.
    const Clef& pattern_clef();

    void onPlaybackStarted(const std::uint64_t&, const std::string&) override {}
    void onPlaybackPosition(const std::uint64_t&, const std::uint32_t&,
                            const std::uint32_t&) override {}
    void onPlaybackFinished(const std::uint64_t& playback, const std::string& reason) override;
    void onRegistryChanged(const std::string& kind, const std::string& name) override;

    Callbacks callbacks_;
    std::optional<Clef> pattern_clef_;
    sdbus::Slot owner_watch_;  // NameOwnerChanged of vibscored's name
};

}  // namespace vibscore::feedback
