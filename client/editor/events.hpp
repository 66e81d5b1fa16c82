#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace vibscore::editor {

// An event of the feedback theme in use and what it plays now (vibscore-feedback's EventScores,
// docs/feedbackd.md): what saving a score "for" an event changes.
struct EventScore {
    std::string event;        // feedbackd's event name: phone-incoming-call
    std::string score;        // the registry score it plays now ("" when a pattern of the theme)
    std::string theme_score;  // the theme's own
    bool assigned = false;    // the user chose `score`
    bool operator==(const EventScore&) const = default;
};

// The event as a phone's settings name it: "incoming call", "new message", "alarm"; an event
// without a name of its own in words ("bell-terminal" -> "bell terminal").
std::string event_label(std::string_view event);

// The events people make a pattern for first (incoming call, messages, alarm, notifications),
// then the others by name.
std::vector<EventScore> in_offer_order(std::vector<EventScore> events);

// What "keep as it was" gives the event back: the score the user had chosen before, or "" (the
// theme's) when it played the theme's.
std::string score_before(const EventScore& before);

}  // namespace vibscore::editor
