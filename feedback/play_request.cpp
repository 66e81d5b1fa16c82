#include "feedback/play_request.hpp"

namespace vibscore::feedback {

std::optional<ScorePlay> score_play(const PlayRequest& request,
                                    const std::function<const Clef&()>& pattern_clef) {
    const ThemeEntry& entry = request.entry;
    ScorePlay play;
    play.clef = entry.clef;
    play.usage = entry.usage;
    play.repeat = request.repeat;
    play.intensity = entry.intensity;
    if (!entry.score.empty()) {
        play.score = entry.score;
        play.intensity *= request.max_strength;
        return play;
    }
    const auto pattern =
        entry.vibra ? vibra_pattern(*entry.vibra, request.max_strength) : VibrationPattern{};
    if (pattern_seconds(pattern) <= 0.0) {
        return std::nullopt;  // nothing to play, and nothing to repeat
    }
    auto on_clef = pattern_on_clef(pattern, request.title, kPatternClefHref, pattern_clef());
    play.score = std::move(on_clef.document);
    play.intensity *= on_clef.intensity;
    play.clef.clear();
    return play;
}

}  // namespace vibscore::feedback
