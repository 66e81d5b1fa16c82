#pragma once

#include <filesystem>
#include <optional>

// A program run from its meson build tree (build/daemon/vibscored, build/client/vibscore) uses
// the files of its own checkout, so a fresh clone works before anything is installed. Nothing
// of the source tree is compiled in: the installed programs stay the same whoever built them.
namespace vibscore {

// The source folder of the meson build tree that `program` lies in: the first folder above it
// holding meson-info/meson-info.json, whose directories.source names it. nullopt for a program
// in no build tree (an installed one), or when that file does not say.
std::optional<std::filesystem::path> source_tree_of(const std::filesystem::path& program);

// The shipped clefs and scores: the source tree's clefs/ for the running program when it lies
// in a build tree whose source has that folder, else the installed folder (VIBSCORE_CLEFDIR).
std::filesystem::path shipped_clefs_folder();

}  // namespace vibscore
