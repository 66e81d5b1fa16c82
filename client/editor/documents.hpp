#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "score/score.hpp"

namespace vibscore::editor {

// Where `show` and `edit` read a score from and where the editor saves it: a VibScore file, or
// a registry name on vibscored.
struct ScoreSource {
    enum class Kind { file, registry };
    Kind kind = Kind::registry;
    std::string name;  // the path, or the registry name
};

// A path (it has a '/', ends in .xml or names an existing file) or else a registry name.
ScoreSource classify_source(const std::string& argument);

// Reads a score file without binding its clefs: the editor opens scores whose clefs it cannot
// find. Throws DocumentError.
Score read_score_file(const std::filesystem::path& path);

// Writes a score file atomically (a temporary file renamed over it). Throws std::runtime_error
// naming the file.
void write_score_file(const std::filesystem::path& path, const Score& score);
// Any document (a clef) likewise.
void write_document_file(const std::filesystem::path& path, const std::string& text);

// The clefs in the score file's directory (NAME.clef.xml: id NAME, href the file name).
std::vector<ClefDeclaration> clefs_beside(const std::filesystem::path& score_file);
// Registry clefs by name: id NAME, href NAME.clef.xml.
std::vector<ClefDeclaration> registry_clefs(const std::vector<std::string>& names);

// The document as vibscored takes it inline: each Clef href reduced to its file name, which is
// how the registry names clefs.
std::string registry_document(Score score);

}  // namespace vibscore::editor
