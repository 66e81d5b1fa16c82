#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "score/document_error.hpp"

namespace vibscore {

// Turns byte offsets into a text into the file:line:column people and editors use. Every
// text-based reader (XML, JSON, RTTTL) reports its problems through one of these.
class LineIndex {
  public:
    LineIndex(std::string_view text, std::string file);

    const std::string& file() const { return file_; }
    // Line and column (1-based, the column counted in bytes) of a byte offset; a negative
    // offset names the whole file.
    SourceLocation at(std::ptrdiff_t offset) const;

  private:
    std::string file_;
    std::vector<std::ptrdiff_t> line_starts_;
};

}  // namespace vibscore
