#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "client/editor/position.hpp"
#include "score/score.hpp"

namespace vibscore::editor {

// What the registry's scores say comes next, learned as a phone keyboard learns words: the
// editor reads every score it can (shipped ones, stored ones, what the user composed before),
// and where the symbols just entered were played before in one of them, the symbol that
// followed there is likely to follow here.
//
// A phrase is a run of notes and rests alike (recurrence.hpp: string, number and length; rests
// by length) ending just before the position asked about; the start of a score counts as one
// symbol, so the first notes of a new score are predicted from how scores start. The longest
// phrase found wins; among continuations of equally long phrases, the most frequent, then one
// at the same beat of its bar, then the one learned first. A note comes whole, tied to the note
// before as it was tied there; its hairpin goes on as it went on there (the hairpin of the
// score's last note where it kept the one of the note before it, its own where it changed).
class PhraseBook {
  public:
    struct Prediction {
        Symbol next;
        int context = 0;  // symbols of the phrase matched (the score's start counts as one)
        int occurrences = 0;
        bool same_beat = false;
    };

    void learn(const Score& score);
    bool empty() const { return phrases_.empty(); }
    std::size_t scores() const { return phrases_.size(); }

    // Every continuation the phrase book knows at `at`, best first (the order next_after
    // picks by; equals in the order learned).
    std::vector<Prediction> candidates(const Score& score, Position at) const;
    std::optional<Prediction> next_after(const Score& score, Position at) const;

  private:
    struct Learned {
        Symbol symbol;  // a note or rest as written, its serials those of its own score
        double beat = 0.0;
    };
    struct Place {
        std::uint32_t phrase;
        std::uint32_t index;  // of the symbol that followed
    };

    std::vector<std::vector<Learned>> phrases_;
    // Where each symbol (by alike_key) was followed by another: the follower's place.
    std::unordered_map<std::uint64_t, std::vector<Place>> followers_;
};

// A score of a registry (a folder's file name or the daemon's name for it).
struct NamedScore {
    std::string name;
    Score score;
};
// What entering `entering` learns from: every registry score but the one of the same name or
// the same music (leave-one-out: a score never proposes itself back).
std::shared_ptr<const PhraseBook> learned_from_others(const std::vector<NamedScore>& registry,
                                                      const NamedScore& entering);

}  // namespace vibscore::editor
