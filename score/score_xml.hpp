#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "score/document_error.hpp"
#include "score/score.hpp"

namespace vibscore {

// Where each part of a score came from, so checks made later (against its clefs) can still name
// the file, line and column at fault.
struct ScoreSourceMap {
    SourceLocation document;
    std::vector<SourceLocation> clefs;                 // per ClefDeclaration
    std::vector<SourceLocation> bars;                  // per Bar
    std::vector<std::vector<SourceLocation>> symbols;  // per Bar, per Symbol
};

struct ParsedScore {
    Score score;
    ScoreSourceMap where;
};

// Reads a VibScore document (thesis Table 3.1). Checks everything that does not need the clefs:
// names, lengths, ranges, limits, and that every bar names a declared clef.
// Throws DocumentError listing each problem with its line and column.
ParsedScore read_score(std::string_view text, const std::string& file);

// Writes a VibScore document that read_score reads back to an equal Score.
std::string write_score(const Score& score);

}  // namespace vibscore
