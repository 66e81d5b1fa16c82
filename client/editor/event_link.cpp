#include "client/editor/event_link.hpp"

#include <sdbus-c++/sdbus-c++.h>

#include "client/editor/feedback_link.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/profile.hpp"
#include "feedback/theme.hpp"
#include "feedback/user_scores.hpp"
#include "json/build_tree.hpp"

namespace vibscore::editor {

EventLink::EventLink() {
    try {
        auto live = std::make_unique<client::FeedbackLink>(sdbus::createSessionBusConnection());
        live->EventScores();  // vibscore-feedback answers, or the file is used
        live_ = std::move(live);
    } catch (const sdbus::Error&) {
        live_.reset();
    }
}

EventLink::~EventLink() = default;

std::vector<EventScore> EventLink::events() {
    std::vector<EventScore> events;
    if (live_) {
        try {
            for (const auto& entry : live_->EventScores()) {
                events.push_back({entry.get<0>(), entry.get<1>(), entry.get<2>(), entry.get<3>()});
            }
            return events;
        } catch (const sdbus::Error& error) {
            throw std::runtime_error("vibscore-feedback: " + error.getMessage());
        }
    }
    try {
        std::vector<Diagnostic> warnings;
        const auto theme =
            // The theme the installed vibscore-feedback reads when it starts, as before the
            // locator: an editor run from its build tree without the service offers no events
            // of its checkout's theme (the editor's end-to-end tests rely on it).
            feedback::load_theme(default_feedback_theme(installed_data()).string(),
                                 feedback::ThemeSearch::from_environment());
        const auto chosen = feedback::read_user_scores(feedback::user_scores_path(), warnings);
        for (const auto& [event, levels] : theme.events()) {
            const auto* entry = theme.lookup(event, feedback::Profile::full);
            EventScore score{event, entry ? entry->score : "", entry ? entry->score : "", false};
            if (const auto mine = chosen.find(event); mine != chosen.end()) {
                score.score = mine->second;
                score.assigned = true;
            }
            events.push_back(score);
        }
        for (const auto& [event, score] : chosen) {
            if (!theme.events().contains(event)) {
                events.push_back({event, score, "", true});
            }
        }
        return events;
    } catch (const std::exception& error) {
        throw std::runtime_error(error.what());
    }
}

void EventLink::assign(const std::string& event, const std::string& score) {
    if (live_) {
        try {
            live_->AssignScore(event, score);
            return;
        } catch (const sdbus::Error& error) {
            throw std::runtime_error("vibscore-feedback: " + error.getMessage());
        }
    }
    try {
        feedback::store_user_score(feedback::user_scores_path(), event, score);
    } catch (const std::exception& error) {
        throw std::runtime_error(error.what());
    }
}

}  // namespace vibscore::editor
