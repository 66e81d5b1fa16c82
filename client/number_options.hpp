#pragma once

#include <CLI/CLI.hpp>

namespace vibscore::client {

// A number option's check, with messages as a person writes them: "not a number: abc",
// "5 is out of range: from -1 to 2147483647" (CLI11's own say "Failed parsing abc as a FLOAT"
// and print bounds as 0.000000).
enum class NumberKind { any, whole };
CLI::Validator number_between(double lowest, double highest, NumberKind kind = NumberKind::any);

}  // namespace vibscore::client
