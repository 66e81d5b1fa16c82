#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "daemon/event_loop.hpp"
#include "feedback-adaptor.h"
#include "feedback/event_table.hpp"
#include "feedback/haptics_link.hpp"
#include "feedback/theme.hpp"

namespace vibscore::feedback {

// The org.sigxcpu.Feedback object (feedback/org.sigxcpu.Feedback.xml documents each member):
// it translates between the bus and the event table, which holds every rule, and plays
// through vibscored. One thread: the loop serving both buses calls everything here.
class FeedbackService final
    : public sdbus::AdaptorInterfaces<org::sigxcpu::Feedback_adaptor,
                                      org::sigxcpu::Feedback::Haptic_adaptor> {
  public:
    // Serves `session_bus` and plays through vibscored on `system_bus`; both are served by
    // `loop`.
    FeedbackService(sdbus::IConnection& session_bus, sdbus::IConnection& system_bus,
                    daemon::EventLoop& loop, Theme theme, FeedbackSettings settings);
    ~FeedbackService();

  private:
    void TriggerFeedback(sdbus::Result<std::uint32_t>&& result, std::string app_id,
                         std::string event, std::map<std::string, sdbus::Variant> hints,
                         std::int32_t timeout) override;
    void EndFeedback(const std::uint32_t& id) override;
    std::string Profile() override { return std::string(to_string(table_.profile())); }
    void Profile(const std::string& value) override;
    bool Vibrate(const std::string& app_id,
                 const std::vector<sdbus::Struct<double, std::uint32_t>>& pattern) override;

    std::string sender() const;

    HapticsLink haptics_;
    EventTable table_;
    daemon::EventLoop::Timer expiry_;  // the earliest timeout of all events
    sdbus::Slot vanish_watch_;         // NameOwnerChanged: a client left the bus
};

}  // namespace vibscore::feedback
