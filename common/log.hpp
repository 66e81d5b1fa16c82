#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

// The daemons' log. Under systemd (stderr is the journal's stream, $JOURNAL_STREAM) each line goes
// to the journal with sd_journal_send: MESSAGE, PRIORITY and the fields it concerns
// (PLAYBACK_ID=, CALLER_UID=, USAGE=, SCORE=, REASON=, as phosphor's lg2 does), so
// `journalctl -u vibscored PLAYBACK_ID=7` finds a playback's lines. Elsewhere a line goes to
// stderr: with the sd-daemon(3) priority prefix ("<6>") into a file or a pipe (a supervisor that
// files by it), as plain text on a terminal ("warning: ..."), the fields after the message.
namespace vibscore::log {

// One journal field: NAME is upper case letters, digits and '_' (journald's rule).
struct Field {
    std::string_view name;
    std::string value;
};
using Fields = std::initializer_list<Field>;

void error(std::string_view message, Fields fields = {});
void warning(std::string_view message, Fields fields = {});
void info(std::string_view message, Fields fields = {});
void debug(std::string_view message, Fields fields = {});

// Debug lines are dropped unless enabled (vibscored --verbose).
void set_verbose(bool verbose);

// How the lines of this process are written, decided once from its stderr and environment.
enum class Sink { journal, stream, terminal };

// The pure parts, for the tests.
namespace detail {
// Whether $JOURNAL_STREAM ("DEVICE:INODE", as systemd sets it) names the file stderr is.
bool names_stream(const char* journal_stream, unsigned long long device, unsigned long long inode);
// The journal entry's fields: MESSAGE=, PRIORITY=, then the line's own (a name journald would
// refuse is dropped rather than losing the entry).
std::vector<std::string> journal_fields(int priority, std::string_view message, Fields fields);
// The line written to stderr, newline included.
std::string stream_line(Sink sink, int priority, std::string_view message, Fields fields);
}  // namespace detail

}  // namespace vibscore::log
