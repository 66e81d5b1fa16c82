#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/editor/events.hpp"

namespace vibscore::client {
class FeedbackLink;
}

namespace vibscore::editor {

// Which score each event of the feedback theme plays for this user, and choosing one: through
// vibscore-feedback on the session bus (org.vibscore.Feedback1: EventScores, AssignScore), or,
// when it is not running, the user's file it reads when it starts and the theme it would read
// ($FEEDBACK_THEME, else the installed default: default_feedback_theme(installed_data())), as
// `vibscore assign` does. Calls throw
// std::runtime_error saying why in words.
class EventLink {
  public:
    EventLink();
    ~EventLink();
    EventLink(const EventLink&) = delete;
    EventLink& operator=(const EventLink&) = delete;

    std::vector<EventScore> events();
    // From now on `event` plays `score` ("" the theme's).
    void assign(const std::string& event, const std::string& score);
    // vibscore-feedback answered (else the file is used).
    bool live() const { return live_ != nullptr; }

  private:
    std::unique_ptr<client::FeedbackLink> live_;  // client/feedback_link.hpp
};

}  // namespace vibscore::editor
