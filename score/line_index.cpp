#include "score/line_index.hpp"

#include <algorithm>

namespace vibscore {

LineIndex::LineIndex(std::string_view text, std::string file) : file_(std::move(file)) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n') {
            line_starts_.push_back(static_cast<std::ptrdiff_t>(i + 1));
        }
    }
}

SourceLocation LineIndex::at(std::ptrdiff_t offset) const {
    if (offset < 0) {
        return {file_};
    }
    const auto next = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
    const auto line = static_cast<int>(next - line_starts_.begin());
    const auto column = static_cast<int>(offset - *(next - 1)) + 1;
    return {file_, line, column};
}

}  // namespace vibscore
