#pragma once

#include <ostream>
#include <string>

namespace vibscore::client {

struct AssignRequest {
    std::string event;
    std::string score;
    bool list = false;        // --list
    bool to_default = false;  // --default
    bool force = false;       // --force: an event the theme does not know (yet)
};

// vibscore assign EVENT SCORE | EVENT --default | --list: the user's own score for a feedback
// event, through vibscore-feedback on the session bus (org.vibscore.Feedback1); when it cannot
// be reached, the choice goes into its file ($XDG_CONFIG_HOME/vibscore/feedback.json) for when
// it runs. docs/feedbackd.md. A score vibscored does not have is refused (exit 1), and so is an
// event the theme does not know, with the nearest names, unless `force` (the event naming rule
// still holds: a name that breaks it is a usage error, exit 2). Returns an exit code.
int assign(const AssignRequest& request, std::ostream& out, std::ostream& err);

}  // namespace vibscore::client
