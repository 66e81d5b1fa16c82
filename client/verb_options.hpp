#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <ostream>
#include <string>

#include "actuator/declaration.hpp"
#include "client/clef_search.hpp"

namespace vibscore::client {

// What `--actuator` without a file stands for: ask vibscored.
inline constexpr const char* kDaemonActuator = "daemon";

// The KIND argument's help: a registry kind, the plural too.
inline constexpr const char* kKindHelp = "score or clef (scores and clefs work too)";

// Registry kinds, the plural too, as vibscored takes them.
CLI::Validator kind_validator();

// `--clefs DIR` (repeatable) on the verbs that load score files: where registry clef names are
// looked up first (docs/score-format.md).
void add_clefs_option(CLI::App& verb, ClefSearch& search);

// `--actuator [FILE]` on the verbs that show what an actuator makes of a score: a file with an
// [actuator] section (vibscored.conf will do), or without one the daemon's declaration. `what`
// says what the verb does with it.
void add_actuator_option(CLI::App& verb, std::string& spec, const std::string& what);

// The declaration `--actuator` names, into `declared` (nothing when not given). exit_ok, or,
// having said why there is none, exit_usage for a bad file and exit_failed when vibscored could
// not give one.
int resolve_actuator(const std::string& spec, std::optional<actuator::Declaration>& declared,
                     std::ostream& err);

}  // namespace vibscore::client
