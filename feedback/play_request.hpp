#pragma once

#include <functional>
#include <optional>
#include <string>

#include "feedback/theme.hpp"
#include "score/clef.hpp"

// What vibscore-feedback asks vibscored to play, and how it becomes a Play call. Pure: the
// event table builds requests, the bus link (haptics_link.hpp) sends them.
namespace vibscore::feedback {

struct PlayRequest {
    ThemeEntry entry;
    std::string title;          // for logs, and a pattern score's title
    int repeat = 0;             // vibscored's: 0 once, -1 until stopped
    double max_strength = 1.0;  // feedbackd's max-haptic-strength
};

// The arguments of vibscored's Play for a request.
struct ScorePlay {
    std::string score;  // a registry score's name, or a score document on the pattern clef
    std::string clef;   // a registry clef to play it with; empty: its own
    std::string usage;
    int repeat = 0;
    double intensity = 1.0;
};

// A registry score plays at its intensity times the maximum strength: its notes keep their
// relations and its full strength becomes the maximum (capping each note would flatten a
// designed tacton's accents). A vibra feedback plays the pattern feedbackd would play, each
// magnitude capped at the maximum, written on the clef `pattern_clef` gives (kPatternClef; it is
// asked for only then). Nothing, when there is nothing to play (a vibra of no length).
std::optional<ScorePlay> score_play(const PlayRequest& request,
                                    const std::function<const Clef&()>& pattern_clef);

// The clef patterns are written on, and the href a score names it by.
inline constexpr const char* kPatternClef = "pattern-ms";
inline constexpr const char* kPatternClefHref = "pattern-ms.clef.xml";

}  // namespace vibscore::feedback
