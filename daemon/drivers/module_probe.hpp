#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "daemon/drivers/module_trust.hpp"

// Driver modules tried out before the daemon loads one: a module's constructors run as soon as
// it is loaded, and one that hangs, crashes or exits must not take the daemon with it. So each
// module is first loaded in a child process of its own, which reports back what the module
// says it is; only a module that loaded there is ever loaded by the daemon, and only when it is
// used (docs/drivers.md, "How modules are loaded"). The child loads the descriptor the trust
// checks opened, in its own session, and cannot start processes or signal the daemon
// (module_confinement.hpp).
namespace vibscore::drivers {

// How long the modules of one scan may take to load, together.
inline constexpr std::chrono::milliseconds kModuleProbeTimeout{2000};

struct ProbedModule {
    std::filesystem::path path;
    std::string name;         // vibscore_driver.name, when it loaded
    std::string description;  // vibscore_driver.description
    std::string error;        // why it did not load ("" when it did)
    bool loaded() const { return error.empty(); }
};

// Loads every module (the open descriptor of each, named by its path) in a confined child
// process of its own, all at once, and waits at most `timeout` for them all; a child still
// loading then is killed. A module loaded when the child found its entry point and the entry
// passed the checks DriverModule::load makes.
std::vector<ProbedModule> probe_modules(const std::vector<TrustedFile>& modules,
                                        std::chrono::milliseconds timeout = kModuleProbeTimeout);

}  // namespace vibscore::drivers
