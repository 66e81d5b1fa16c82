#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "daemon/event_loop.hpp"
#include "feedback-adaptor.h"
#include "feedback/haptics_link.hpp"
#include "feedback/profile.hpp"
#include "feedback/theme.hpp"

namespace vibscore::feedback {

// libfeedback's LfbEventEndReason, as FeedbackEnded sends it.
namespace end_reason {
inline constexpr std::uint32_t natural = 0;
inline constexpr std::uint32_t expired = 1;
inline constexpr std::uint32_t explicit_end = 2;
inline constexpr std::uint32_t not_found = 0xffffffff;  // -1
}  // namespace end_reason

struct ServiceSettings {
    Profile profile = Profile::full;
    std::string haptic_usage = "touch";  // vibscored's usage for Haptic.Vibrate patterns
};

// The org.sigxcpu.Feedback object (feedback/org.sigxcpu.Feedback.xml documents each member):
// events become scores through the theme and play through vibscored; what vibscored reports
// becomes FeedbackEnded. One thread: the loop serving both buses calls everything here.
class FeedbackService final
    : public sdbus::AdaptorInterfaces<org::sigxcpu::Feedback_adaptor,
                                      org::sigxcpu::Feedback::Haptic_adaptor> {
  public:
    // Serves `session_bus` and plays through vibscored on `system_bus`; both are served by
    // `loop`.
    FeedbackService(sdbus::IConnection& session_bus, sdbus::IConnection& system_bus,
                    daemon::EventLoop& loop, Theme theme, ServiceSettings settings);
    ~FeedbackService();

  private:
    void TriggerFeedback(sdbus::Result<std::uint32_t>&& result, std::string app_id,
                         std::string event, std::map<std::string, sdbus::Variant> hints,
                         std::int32_t timeout) override;
    void EndFeedback(const std::uint32_t& id) override;
    std::string Profile() override { return std::string(to_string(profile_)); }
    void Profile(const std::string& value) override;
    bool Vibrate(const std::string& app_id,
                 const std::vector<sdbus::Struct<double, std::uint32_t>>& pattern) override;

    struct Event {
        std::string sender;  // its client's bus name: the event ends when the client leaves
        feedback::Profile level = Profile::full;  // the theme level its feedback came from
        std::uint64_t playback = 0;
        std::optional<std::uint64_t> expires_us;  // a timeout's end
        std::uint32_t end_reason = end_reason::natural;
        bool ending = false;  // Stop asked; FeedbackEnded follows vibscored's report
    };

    // Plays an entry through vibscored: the playback id, or 0 (never an id) when it does not.
    std::uint64_t play(const ThemeEntry& entry, const std::string& title, int repeat);
    // Ends an event's feedback early with `reason`.
    void end(std::uint32_t id, std::uint32_t reason);
    void ended(std::map<std::uint32_t, Event>::iterator event);
    void end_where(const std::function<bool(const Event&)>& which, std::uint32_t reason);
    void arm_expiry();
    void expire();
    // vibscored's reports.
    void playback_finished(std::uint64_t playback, const std::string& reason);
    void haptics_gone();

    HapticsLink haptics_;
    Theme theme_;
    ServiceSettings settings_;
    feedback::Profile profile_;
    std::uint32_t next_id_ = 1;
    std::map<std::uint32_t, Event> events_;
    std::optional<std::uint64_t> haptic_playback_;  // the last Vibrate pattern
    daemon::EventLoop::Timer expiry_;               // the earliest timeout of all events
    sdbus::Slot vanish_watch_;                      // NameOwnerChanged: a client left the bus
};

}  // namespace vibscore::feedback
