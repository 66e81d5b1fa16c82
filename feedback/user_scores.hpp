#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "score/document_error.hpp"

// The user's own score for an event: a small JSON file in the user's config directory, which
// vibscore-feedback reads at start and watches, and which AssignScore and `vibscore assign`
// write (docs/feedbackd.md, "Your own score for an event"):
//
//   { "events": { "phone-incoming-call": "my-ring", "message-new-sms": "confirm" } }
//
// Each member of "events" is an event name and a registry score name.
//
// The file is bounded so that it always reads back whole: at most kMaxAssignments events, each
// name at most 64 characters, so a file this code writes stays near 40 kB, far below the JSON
// reader's limit (max_json_file_bytes, 1 MiB); a write that would pass that limit anyway (members
// added by hand) is refused, never made.
namespace vibscore::feedback {

using UserScores = std::map<std::string, std::string, std::less<>>;

// At most this many events have a score of the user's own (docs/feedbackd.md, "Limits").
inline constexpr std::size_t kMaxAssignments = 256;
inline constexpr std::size_t kMaxEventNameLength = 64;
inline constexpr std::string_view kEventNameRule =
    "an event name is 1 to 64 characters: lower-case words of a-z and 0-9 joined by single "
    "hyphens, as phone-incoming-call";

// Whether `name` follows the event naming rule (kEventNameRule), as the freedesktop event
// names (feedbackd's) do. An event the theme in use has may be assigned whatever its name.
bool is_event_name(std::string_view name);

// A store that would pass a limit of the file: kMaxAssignments events, or the reader's size.
class AssignmentLimit : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// $XDG_CONFIG_HOME/vibscore/feedback.json, else $HOME/.config/vibscore/feedback.json.
std::filesystem::path user_scores_path();

// The file's choices: none when it does not exist. Throws DocumentError naming the file (and
// the line:column) when it does not read as a whole: not a regular file (a FIFO would hold the
// reader), not JSON, larger than the reader's limit, "events" not an object. One wrong entry does
// not cost the others: an event or score that is not a name, a value that is not a string, and the
// entries past the kMaxAssignments-th are each read past with a warning at their place; so are
// other members, as a newer version may add some.
UserScores read_user_scores(const std::filesystem::path& file, std::vector<Diagnostic>& warnings);

// Stores `score` for `event` ("" removes the event's choice), keeping everything else in the
// file, atomically; makes the directory (0700) when it is missing. Throws std::invalid_argument
// for a name that is not one, AssignmentLimit for a new event beyond kMaxAssignments or a file
// that would be larger than the reader's limit, DocumentError when the file exists but does not
// read (it is left as it is), std::system_error when it cannot be written.
void store_user_score(const std::filesystem::path& file, const std::string& event,
                      const std::string& score);

// Removes the temporaries an interrupted store (a crash, SIGKILL) left beside `file`
// (".feedback.json.tmp-*"), and only those: the directory may hold other programs' files.
// Returns the paths removed. Throws std::system_error when one cannot be removed.
std::vector<std::filesystem::path> remove_stale_temporaries_of(const std::filesystem::path& file);

// Makes the directory of the user's file when it is missing, readable by the user alone (0700;
// its parents as the umask gives). Throws std::system_error.
void make_user_directory(const std::filesystem::path& directory);

// Throws std::invalid_argument naming which and the rule (both are registry-style names).
void check_event_and_score(const std::string& event, const std::string& score);

}  // namespace vibscore::feedback
