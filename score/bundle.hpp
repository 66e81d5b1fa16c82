#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "score/clef.hpp"
#include "score/score.hpp"
#include "score/score_xml.hpp"

namespace vibscore {

// A score together with the clefs it declares, checked against each other: every note's string
// and number exist in its bar's clef and the whole piece stays within limits. Ready to render.
struct ScoreBundle {
    std::string file;
    Score score;
    ScoreSourceMap where;
    std::map<std::string, Clef, std::less<>> clefs;  // by declaration id

    const Clef& clef_of(const Bar& bar) const { return clefs.at(bar.clef); }
};

// Finds the clef a declaration names. Throws DocumentError when it cannot.
using ClefResolver = std::function<Clef(const ClefDeclaration&, const SourceLocation& declared_at)>;

// Resolves every declared clef and checks the score against them; reports all problems at once.
ScoreBundle bind_clefs(ParsedScore parsed, std::string file, const ClefResolver& resolve);

// Reads a whole document file, refusing files over limits::document_bytes.
std::string read_document_file(const std::filesystem::path& path);

// The two kinds of document: what the registry holds, the client reads and the bus names
// "score" and "clef".
enum class DocumentKind { score, clef };

std::string_view to_string(DocumentKind kind);

// Accepts "score", "scores", "clef" and "clefs".
std::optional<DocumentKind> parse_document_kind(std::string_view text);

// Tells a VibScore from a VibClef by its root element; throws DocumentError for anything else.
DocumentKind document_kind(std::string_view text, const std::string& file);

Clef load_clef_file(const std::filesystem::path& path);

// A registry clef found by name, for a score file whose clef href is a bare name with no file
// beside the score: the clef, and where it came from ("registry", a path), for messages.
struct NamedClef {
    Clef clef;
    std::string origin;
};
// Looks up registry clef `name` (`find`: nullopt when there is none; may throw DocumentError for
// a clef that is there but invalid), and says where it looks, for the message when it finds none.
struct NamedClefLookup {
    std::function<std::optional<NamedClef>(const std::string& name)> find;
    std::string places;

    explicit operator bool() const { return static_cast<bool>(find); }
};

// Loads a score file and its clefs, by the one rule of docs/score-format.md ("How a score names
// its clefs"): an href is a path relative to the score's folder; when no file is there and the
// href is a bare registry clef name (NAME.clef.xml), `named` looks it up. `origins`, if given,
// receives where each declared clef came from, by clef id.
ScoreBundle load_score_file(const std::filesystem::path& path, const NamedClefLookup& named = {},
                            std::map<std::string, std::string>* origins = nullptr);

}  // namespace vibscore
