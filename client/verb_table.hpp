#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string_view>
#include <vector>

#include "client/clef_search.hpp"

namespace vibscore::client {

// What every verb may need besides its own options: where the clefs a score names are found.
struct VerbContext {
    ClefSearch clef_search;
};

// Runs a verb once the command line is parsed into the options it declared; the exit code.
using VerbHandler = std::function<int()>;

// One command of `vibscore` (`check`, `clef fit`). The general --help, each verb's --help, the
// manual page check and the bash completion's verbs and options all come from this table, so a
// verb or option exists in all of them or in none.
struct Verb {
    std::string_view name;
    std::string_view help;  // one line in `vibscore --help`, the first of `vibscore VERB --help`
    // Declares the verb's arguments and options on its command, bound to storage the returned
    // handler owns (CLI11 writes through references, so the two are made together). Null for a
    // verb made only of sub-verbs.
    VerbHandler (*declare)(CLI::App& command, VerbContext& context) = nullptr;
    // What the bash completion offers for each argument, in order: sources separated by commas,
    // each a file pattern (has a '*'), @scores or @clefs (the registry's), @kind (the registry's
    // names of the kind the word before names), @events (vibscore assign --list), @drivers, or a
    // word as it is; "..." at the end of the last stands for every later argument too.
    std::vector<std::string_view> completion = {};
    std::vector<Verb> subverbs = {};  // `clef`: `fit`
    std::string_view footer = {};     // after the options in the verb's --help
};

// Every verb, in the order `vibscore --help` lists them.
const std::vector<Verb>& verbs();

}  // namespace vibscore::client
