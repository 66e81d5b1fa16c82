#pragma once

#include <string>
#include <vector>

namespace vibscore::testing {

struct CommandResult {
    int exit_code = -1;  // 128 + signal number if it was killed
    std::string out;
    std::string err;
};

// Runs a program (no shell) to completion and captures its output.
CommandResult run_command(const std::vector<std::string>& argv);

// The value of an environment variable the test runner must set; fails the test if unset.
std::string required_env(const char* name);

}  // namespace vibscore::testing
