#pragma once

#include <functional>
#include <string>

#include "client/offline_verbs.hpp"

// What check, render and show ask vibscored for when they are given a registry name or
// `--actuator daemon`: the registry's scores, and the clefs the daemon plays a score through.
namespace vibscore::client {

// For ClefSearch::registry_score: vibscored's registry score NAME (within a few seconds). Throws
// std::runtime_error with the daemon's answer in words (not running, not found).
std::function<std::string(const std::string& name)> registry_score_fetcher();

// For `--actuator daemon`: each clef of the score as vibscored binds it (BarClefs): mapped by
// [clefs] to another registry clef, fitted to the declared actuator (fit = auto, fitted exactly
// as `vibscore get clef NAME --device` fits it: the registry clef through render::fit_clef), or
// as written. A clef the score brings from a file is one vibscored is sent along with the score:
// fitted when fit = auto, else played as written. Throws std::runtime_error when vibscored
// cannot be asked.
DeviceClefBinder daemon_clef_binder();

}  // namespace vibscore::client
