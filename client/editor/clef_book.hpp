#pragma once

#include <optional>
#include <string>
#include <vector>

#include "score/clef.hpp"
#include "score/score.hpp"

namespace vibscore::editor {

// A clef the editor could read: where a bar's clef id leads, and what it says there.
struct KnownClef {
    ClefDeclaration declaration;  // its id, and the href a score declares it by
    Clef clef;
    bool shipped = false;  // installed with the system: a clef edited from it is saved anew
    bool operator==(const KnownClef&) const = default;
};

// The clefs the session read (the score's own, the registry's, the files beside a file score),
// found by id.
class ClefBook {
  public:
    ClefBook() = default;
    explicit ClefBook(std::vector<KnownClef> clefs) : clefs_(std::move(clefs)) {}

    const std::vector<KnownClef>& clefs() const { return clefs_; }
    const KnownClef* find(const std::string& id) const;
    // Adds or replaces the clef of that id.
    void put(KnownClef clef);
    bool operator==(const ClefBook&) const = default;

  private:
    std::vector<KnownClef> clefs_;
};

}  // namespace vibscore::editor
