#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "score/document_error.hpp"

// The user's own score for an event: a small JSON file in the user's config directory, which
// vibscore-feedback reads at start and watches, and which AssignScore and `vibscore assign`
// write (docs/feedbackd.md, "Your own score for an event"):
//
//   { "events": { "phone-incoming-call": "my-ring", "message-new-sms": "confirm" } }
//
// Each member of "events" is an event name and a registry score name.
namespace vibscore::feedback {

using UserScores = std::map<std::string, std::string, std::less<>>;

// $XDG_CONFIG_HOME/vibscore/feedback.json, else $HOME/.config/vibscore/feedback.json.
std::filesystem::path user_scores_path();

// The file's choices: none when it does not exist. Throws DocumentError at the file:line:column
// of what is wrong (a name that is not one, a value that is not a string); other members are
// read past with a warning, as a newer version may add some.
UserScores read_user_scores(const std::filesystem::path& file, std::vector<Diagnostic>& warnings);

// Stores `score` for `event` ("" removes the event's choice), keeping everything else in the
// file, atomically; makes the directory (0700) when it is missing. Throws std::invalid_argument
// for a name that is not one, DocumentError when the file exists but does not read (it is left
// as it is), std::system_error when it cannot be written.
void store_user_score(const std::filesystem::path& file, const std::string& event,
                      const std::string& score);

// Makes the directory of the user's file when it is missing, readable by the user alone (0700;
// its parents as the umask gives). Throws std::system_error.
void make_user_directory(const std::filesystem::path& directory);

// Throws std::invalid_argument naming which and the rule (both are registry-style names).
void check_event_and_score(const std::string& event, const std::string& score);

}  // namespace vibscore::feedback
