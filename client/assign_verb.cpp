#include "client/assign_verb.hpp"

#include <sdbus-c++/sdbus-c++.h>

#include <algorithm>
#include <iomanip>
#include <optional>
#include <stdexcept>
#include <vector>

#include "client/editor/feedback_link.hpp"
#include "client/offline_verbs.hpp"
#include "common/closest_name.hpp"
#include "common/quoted_text.hpp"
#include "dbus/feedback1_names.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "feedback/user_scores.hpp"
#include "haptics1-proxy.h"

namespace vibscore::client {

namespace {

// vibscored's registry, asked which scores it holds.
class Registry : public sdbus::ProxyInterfaces<org::vibscore::Haptics1_proxy> {
  public:
    explicit Registry(std::unique_ptr<sdbus::IConnection> connection)
        : ProxyInterfaces(*connection, dbus::service_name(haptics1::kBusName),
                          dbus::object_path(haptics1::kObjectPath)),
          connection_(std::move(connection)) {
        registerProxy();
    }
    ~Registry() { unregisterProxy(); }

  private:
    void onPlaybackStarted(const uint64_t&, const std::string&) override {}
    void onPlaybackPosition(const uint64_t&, const uint32_t&, const uint32_t&) override {}
    void onPlaybackFinished(const uint64_t&, const std::string&) override {}
    void onRegistryChanged(const std::string&, const std::string&) override {}
    std::unique_ptr<sdbus::IConnection> connection_;
};

// " (did you mean NAME?)" when one of `names` is near `word`, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& names) {
    const auto meant = closest_name(word, names);
    return meant ? " (did you mean " + *meant + "?)" : "";
}

// Whether vibscored has the score: a refusal (exit_failed) when it has not, with the nearest
// name; nothing when it has or cannot be asked (then a warning says the score is not checked:
// the choice is stored, and the event plays the theme's until the score is there).
std::optional<int> refuse_unknown_score(const std::string& score, std::ostream& err) {
    std::vector<std::string> names;
    try {
        Registry registry(sdbus::createSystemBusConnection());
        for (const auto& entry : registry.List("score")) {
            names.push_back(entry.get<0>());
        }
    } catch (const sdbus::Error& error) {
        err << "vibscore: warning: vibscored cannot be asked whether it has the score "
            << quoted_text(score) << " (" << error.getMessage() << "): not checked\n";
        return std::nullopt;
    }
    if (std::find(names.begin(), names.end(), score) != names.end()) {
        return std::nullopt;
    }
    err << "vibscore: vibscored has no score " << quoted_text(score) << did_you_mean(score, names)
        << "; 'vibscore list' shows the scores, 'vibscore compose' stores one\n";
    return exit_failed;
}

// The errors that mean "vibscore-feedback is not there": no session bus, no one (and nothing
// activatable) owns the name, or another program (feedbackd) does.
bool not_reachable(const sdbus::Error& error) {
    static const std::vector<std::string> names{
        "org.freedesktop.DBus.Error.ServiceUnknown",   "org.freedesktop.DBus.Error.NameHasNoOwner",
        "org.freedesktop.DBus.Error.UnknownInterface", "org.freedesktop.DBus.Error.UnknownMethod",
        "org.freedesktop.DBus.Error.UnknownObject",    "org.freedesktop.DBus.Error.NoReply",
        "org.freedesktop.DBus.Error.Disconnected"};
    return std::find(names.begin(), names.end(), error.getName()) != names.end() ||
           error.getName().starts_with("org.freedesktop.DBus.Error.Spawn");
}

std::string why(const sdbus::Error& error) {
    return error.getName() == "org.freedesktop.DBus.Error.UnknownInterface" ||
                   error.getName() == "org.freedesktop.DBus.Error.UnknownMethod"
               ? std::string(feedback1::kBusName) + " is served by another program (feedbackd?)"
               : "vibscore-feedback cannot be reached on the session bus";
}

int list_file(const std::filesystem::path& file, const std::string& reason, std::ostream& out,
              std::ostream& err) {
    std::vector<Diagnostic> warnings;
    const auto scores = feedback::read_user_scores(file, warnings);
    for (const auto& warning : warnings) {
        err << "vibscore: warning: " << format(warning) << "\n";
    }
    err << "vibscore: " << reason << "; your own scores, from " << file.string()
        << " (the theme's events are not known without it):\n";
    for (const auto& [event, score] : scores) {
        out << std::left << std::setw(28) << event << " " << score << "\n";
    }
    return exit_ok;
}

int list_live(FeedbackLink& link, std::ostream& out) {
    for (const auto& entry : link.EventScores()) {
        const auto& event = entry.get<0>();
        const auto& score = entry.get<1>();
        const auto& theme_score = entry.get<2>();
        const bool assigned = entry.get<3>();
        std::string note;
        if (assigned) {
            note = "yours" +
                   (theme_score.empty() ? std::string() : " (the theme's: " + theme_score + ")");
        } else if (score.empty()) {
            note = "the theme's pattern";
        }
        out << std::left << std::setw(28) << event << " ";
        if (note.empty()) {
            out << (score.empty() ? "-" : score) << "\n";
        } else {
            out << std::setw(24) << (score.empty() ? "-" : score) << " " << note << "\n";
        }
    }
    return exit_ok;
}

}  // namespace

int assign(const AssignRequest& request, std::ostream& out, std::ostream& err) {
    if (request.list != request.event.empty() ||
        (!request.list && request.to_default != request.score.empty()) ||
        (request.list && (request.to_default || !request.score.empty() || request.force))) {
        err << "vibscore: assign takes EVENT SCORE, EVENT --default or --list\n"
               "Run 'vibscore assign --help' for usage.\n";
        return exit_usage;
    }
    const bool choosing = !request.list && !request.score.empty();
    if (!request.list) {
        try {
            feedback::check_event_and_score(request.event, request.score);
        } catch (const std::invalid_argument& error) {
            err << "vibscore: " << error.what() << "\n";
            return exit_usage;
        }
    }
    if (choosing && request.force && !feedback::is_event_name(request.event)) {
        err << "vibscore: event " << quoted_text(request.event)
            << " is not an event name, even with --force (" << feedback::kEventNameRule << ")\n";
        return exit_usage;
    }
    if (choosing) {
        if (const auto refused = refuse_unknown_score(request.score, err)) {
            return *refused;
        }
    }
    std::string reason;
    std::unique_ptr<sdbus::IConnection> bus;
    try {
        bus = sdbus::createSessionBusConnection();
    } catch (const sdbus::Error& error) {
        reason = "there is no session bus (" + error.getMessage() + ")";
    }
    if (bus) {
        try {
            FeedbackLink link(std::move(bus));
            if (request.list) {
                return list_live(link, out);
            }
            if (choosing && !request.force) {
                // The theme's events and those already chosen: a typo is caught here, not
                // found out when the phone rings without the chosen score.
                std::vector<std::string> known;
                for (const auto& entry : link.EventScores()) {
                    known.push_back(entry.get<0>());
                }
                if (std::find(known.begin(), known.end(), request.event) == known.end()) {
                    err << "vibscore: event " << quoted_text(request.event)
                        << " is not in the theme" << did_you_mean(request.event, known)
                        << "; --force assigns it all the same, for an event the theme does not "
                           "know yet\n";
                    return exit_failed;
                }
            }
            link.AssignScore(request.event, request.score);
            out << request.event << " plays "
                << (request.score.empty() ? "the theme's score" : request.score)
                << " from now on\n";
            return exit_ok;
        } catch (const sdbus::Error& error) {
            if (!not_reachable(error)) {
                err << "vibscore: " << error.getMessage() << "\n";
                return error.getName() == feedback1::errors::kInvalidArgs ? exit_usage
                                                                          : exit_failed;
            }
            reason = why(error);
        }
    }
    // Without vibscore-feedback: its file, which it reads when it starts. The theme it will
    // use is not known here, so the event naming rule stands in for it.
    if (choosing && !feedback::is_event_name(request.event)) {
        err << "vibscore: event " << quoted_text(request.event)
            << " is not an event name, and without vibscore-feedback the theme cannot be asked ("
            << feedback::kEventNameRule << ")\n";
        return exit_usage;
    }
    try {
        const auto file = feedback::user_scores_path();
        if (request.list) {
            return list_file(file, reason, out, err);
        }
        feedback::store_user_score(file, request.event, request.score);
        out << request.event << " plays "
            << (request.score.empty() ? "the theme's score" : request.score)
            << " when vibscore-feedback runs (" << reason << "; stored in " << file.string()
            << ")\n";
        return exit_ok;
    } catch (const std::exception& error) {
        err << "vibscore: " << error.what() << "\n";
        return exit_failed;
    }
}

}  // namespace vibscore::client
