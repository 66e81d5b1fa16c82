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
    std::filesystem::path shipped;  // default: shipped_clefs_folder() (json/build_tree.hpp)
    // The text of vibscored's registry score NAME, for check, render and show given a name.
    // Throws std::runtime_error saying why there is none (no vibscored, no such score); unset:
    // there is no registry to ask.
    std::function<std::string(const std::string& name)> registry_score;

    ClefSearch();

    // For load_score_file. The origin it reports is the clef file's path, or "registry".
    NamedClefLookup lookup() const;
};

inline constexpr const char* kRegistryOrigin = "registry";

// A score file loaded by the rule above, with where each of its clefs came from, by clef id.
struct LoadedScore {
    ScoreBundle bundle;
    std::map<std::string, std::string> clef_origins;
};
LoadedScore load_score(const std::filesystem::path& path, const ClefSearch& search);

// The rule of play, info and show for a document argument, so check and render follow it too:
// a path (it has a '/', ends in .xml, or names a file that exists) is read as a file, and a file
// path always wins; anything else is a registry name. (editor::classify_source says the same
// for the editor, which this library does not link.)
bool names_a_file(const std::string& argument);

// A registry document named on the command line: vibscored's score NAME with its clefs found by
// the clef rule above, or else the clef NAME the clef rule finds (--clefs, vibscored, the
// shipped clefs). Exactly one of the two is set.
struct RegistryDocument {
    std::optional<LoadedScore> score;
    std::optional<Clef> clef;
};
// Throws DocumentError for an invalid document, and std::runtime_error saying once where it
// looked when NAME is neither a file nor a registry score nor a clef.
RegistryDocument load_registry_document(const std::string& name, const ClefSearch& search);

}  // namespace vibscore::client
