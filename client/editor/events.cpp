#include "client/editor/events.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace vibscore::editor {

namespace {

// feedbackd's event names (its themes and the Event Naming Specification), the ones a person
// composes for first, in that order, with the words a phone's settings use for them.
constexpr std::array<std::pair<std::string_view, std::string_view>, 10> kWanted{{
    {"phone-incoming-call", "incoming call"},
    {"message-new-instant", "new message"},
    {"message-new-sms", "new SMS"},
    {"message-new-email", "new email"},
    {"alarm-clock-elapsed", "alarm"},
    {"notification-new-generic", "notification"},
    {"phone-missed-call", "missed call"},
    {"timeout-completed", "timer done"},
    {"message-new-cellbroadcast", "emergency alert"},
    {"phone-hangup", "call ended"},
}};

int rank(std::string_view event) {
    for (std::size_t i = 0; i < kWanted.size(); ++i) {
        if (kWanted[i].first == event) {
            return static_cast<int>(i);
        }
    }
    return static_cast<int>(kWanted.size());
}

}  // namespace

std::string event_label(std::string_view event) {
    for (const auto& [name, label] : kWanted) {
        if (name == event) {
            return std::string(label);
        }
    }
    std::string words(event);
    std::replace(words.begin(), words.end(), '-', ' ');
    return words;
}

std::vector<EventScore> in_offer_order(std::vector<EventScore> events) {
    std::stable_sort(events.begin(), events.end(), [](const EventScore& a, const EventScore& b) {
        const int ra = rank(a.event);
        const int rb = rank(b.event);
        return ra != rb ? ra < rb : a.event < b.event;
    });
    return events;
}

std::string score_before(const EventScore& before) {
    return before.assigned ? before.score : "";
}

}  // namespace vibscore::editor
