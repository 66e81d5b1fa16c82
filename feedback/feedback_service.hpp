#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/event_loop.hpp"
#include "feedback-adaptor.h"
#include "feedback/event_table.hpp"
#include "feedback/haptics_link.hpp"
#include "feedback/theme.hpp"
#include "feedback/user_scores_watch.hpp"
#include "feedback/user_scores_writer.hpp"
#include "feedback1-adaptor.h"

namespace vibscore::feedback {

// The org.sigxcpu.Feedback object (feedback/org.sigxcpu.Feedback.xml and
// org.vibscore.Feedback1.xml document each member): it translates between the bus and the
// event table, which holds every rule, and plays through vibscored. One thread: the loop
// serving both buses calls everything here; only the user's file is written on a thread of its
// own (UserScoresWriter), whose outcome comes back to the loop.
class FeedbackService final
    : public sdbus::AdaptorInterfaces<org::sigxcpu::Feedback_adaptor,
                                      org::sigxcpu::Feedback::Haptic_adaptor,
                                      org::vibscore::Feedback1_adaptor> {
  public:
    // Serves `session_bus` and plays through vibscored on `system_bus`; both are served by
    // `loop`. The user's scores are read from `user_scores` (user_scores.hpp) now and whenever
    // it changes; without one, events play the theme's.
    FeedbackService(sdbus::IConnection& session_bus, sdbus::IConnection& system_bus,
                    daemon::EventLoop& loop, Theme theme, FeedbackSettings settings,
                    std::optional<std::filesystem::path> user_scores);
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

    std::vector<sdbus::Struct<std::string, std::string, std::string, bool>> EventScores() override;
    void AssignScore(sdbus::Result<>&& result, std::string event, std::string score) override;
    // Throws sdbus::Error (InvalidArgs) for an event or score AssignScore does not take.
    void check_assignment(const std::string& event, const std::string& score) const;
    void assigned(sdbus::Result<>& result, const std::string& event, const std::string& score,
                  const std::string& caller, std::exception_ptr error);

    std::string sender() const;
    // Reads the user's scores into the table; a file that does not read leaves them as they
    // were, with a warning.
    void load_user_scores();

    HapticsLink haptics_;
    EventTable table_;
    daemon::EventLoop::Timer expiry_;  // the earliest timeout of all events
    sdbus::Slot vanish_watch_;         // NameOwnerChanged: a client left the bus
    std::optional<std::filesystem::path> user_scores_;
    std::unique_ptr<FileWatch> user_scores_watch_;
    bool user_scores_read_ = false;  // the file read once at least
    // Last: destroyed first, it finishes the queued stores before anything they report to.
    std::unique_ptr<UserScoresWriter> writer_;
};

}  // namespace vibscore::feedback
