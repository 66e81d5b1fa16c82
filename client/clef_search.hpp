#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "score/bundle.hpp"

namespace vibscore::client {

// Where the client finds a clef that a score file names by registry name (href "NAME.clef.xml"
// with no such file beside the score), in this order: the folders given with --clefs, then
// vibscored's registry (when it runs), then the shipped clefs folder (the installed one; for a
// vibscore run from its build tree, its source tree's clefs/). The same rule for check, info,
// render, show, play, compose and convert (docs/score-format.md).
struct ClefSearch {
    std::vector<std::filesystem::path> folders;  // --clefs DIR, in order
    // The text of the daemon's registry clef NAME; nullopt when it has none or does not run.
    std::function<std::optional<std::string>(const std::string& name)> registry;
    std::filesystem::path shipped;  // default: shipped_clefs_folder()

    ClefSearch();

    // For load_score_file. The origin it reports is the clef file's path, or "registry".
    NamedClefLookup lookup() const;
};

inline constexpr const char* kRegistryOrigin = "registry";

// The source tree's clefs/ when `program` lies in a meson build tree (a folder above it holds
// meson-info/meson-info.json, which names the source folder); nullopt for an installed program.
std::optional<std::filesystem::path> source_tree_clefs(const std::filesystem::path& program);

// The shipped clefs: the source tree's for a program run from its build tree (so a fresh
// checkout's build/client/vibscore finds lra-phone with nothing installed), else the installed
// folder.
std::filesystem::path shipped_clefs_folder();

// A score file loaded by the rule above, with where each of its clefs came from, by clef id.
struct LoadedScore {
    ScoreBundle bundle;
    std::map<std::string, std::string> clef_origins;
};
LoadedScore load_score(const std::filesystem::path& path, const ClefSearch& search);

}  // namespace vibscore::client
