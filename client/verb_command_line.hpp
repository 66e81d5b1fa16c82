#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "client/verb_table.hpp"

namespace vibscore::client {

// The hidden first argument that prints the completion words (completion_words) instead of
// running a verb; completion/vibscore.bash asks it for the verbs and their options.
inline constexpr const char* kCompletionWordsFlag = "--completion-words";

// `vibscore ARGS...`: builds the command line from the verb table, parses it and runs the chosen
// verb; the exit code (offline_verbs.hpp's ExitCode).
int run_command_line(int argc, char** argv);

// The first word of `words` (argv after the program) that names no verb of `table` where a verb
// must stand (the first word not an option, and the one after a verb made of sub-verbs), as a
// usage error's message naming the closest verb; empty when every verb word is known. Checked
// before parsing, so `vibscore calibrat --help` is refused as `vibscore calibrat` is.
std::string unknown_verb_message(const std::vector<Verb>& table,
                                 const std::vector<std::string>& words);

}  // namespace vibscore::client
