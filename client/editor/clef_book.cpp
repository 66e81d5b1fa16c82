#include "client/editor/clef_book.hpp"

#include <algorithm>

namespace vibscore::editor {

const KnownClef* ClefBook::find(const std::string& id) const {
    const auto found = std::find_if(clefs_.begin(), clefs_.end(), [&](const KnownClef& known) {
        return known.declaration.id == id;
    });
    return found == clefs_.end() ? nullptr : &*found;
}

void ClefBook::put(KnownClef clef) {
    for (auto& known : clefs_) {
        if (known.declaration.id == clef.declaration.id) {
            known = std::move(clef);
            return;
        }
    }
    clefs_.push_back(std::move(clef));
}

}  // namespace vibscore::editor
