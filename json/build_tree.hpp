#pragma once

#include <filesystem>
#include <optional>

// Where the data a program ships lies: the clefs and scores, vibscore-feedback's default theme,
// the client's documents. One rule for all three programs: installed, the folders config.h names
// (the install prefix); run from its meson build tree (build/daemon/vibscored,
// build/client/vibscore), the files of its own checkout, so a fresh clone works before anything
// is installed. Nothing of the source tree is compiled in: the installed programs stay the same
// whoever built them.
namespace vibscore {

// The source folder of the meson build tree that `program` lies in: the first folder above it
// holding meson-info/meson-info.json, whose directories.source names it. nullopt for a program
// in no build tree (an installed one), or when that file does not say.
std::optional<std::filesystem::path> source_tree_of(const std::filesystem::path& program);

struct DataLocations {
    std::filesystem::path clefs;           // the shipped clefs and scores (a folder)
    std::filesystem::path feedback_theme;  // vibscore-feedback's default theme (a file)
    std::filesystem::path docs;            // the client's documents, docs/NAME.md (a folder)
};

// Where `make install` puts them (VIBSCORE_CLEFDIR, VIBSCORE_FEEDBACK_THEME,
// VIBSCORE_CLIENT_DOCDIR).
DataLocations installed_data();

// For `program`: each item from the source tree of the build tree it lies in when that
// checkout has it (clefs/, feedback/themes/default.json, docs/), else the installed one. An
// item is decided on its own: a checkout without clefs/ still gives its theme.
DataLocations data_locations_of(const std::filesystem::path& program);

// data_locations_of the running program (/proc/self/exe; installed_data() when unreadable).
DataLocations data_locations();

// The shipped clefs and scores of the running program: data_locations().clefs.
std::filesystem::path shipped_clefs_folder();

// The theme vibscore-feedback reads when started without --theme: $FEEDBACK_THEME when set
// and not empty, else `located.feedback_theme` (for vibscore-feedback, data_locations()'s). The
// editor, when vibscore-feedback does not answer, passes installed_data(): the theme of the
// installed service it tells the user to start.
std::filesystem::path default_feedback_theme(const DataLocations& located);

}  // namespace vibscore
