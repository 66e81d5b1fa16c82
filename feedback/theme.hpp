#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <vector>

#include "feedback/profile.hpp"
#include "feedback/vibra_feedback.hpp"
#include "json/json_document.hpp"
#include "score/document_error.hpp"

// Which score an event plays: a theme maps event names to scores per profile. Two formats are
// read (docs/feedbackd.md): vibscore's own (event -> a registry score, its usage and strength)
// and feedbackd's theme JSON, whose vibra entries play as feedbackd plays them, so a device's
// existing theme keeps working.
namespace vibscore::feedback {

struct ThemeSearch;

struct ThemeEntry {
    // A registry score by name, or (from a feedbackd theme) a vibra feedback.
    std::string score;
    std::optional<VibraFeedback> vibra;
    std::string clef;        // a registry clef to play the score with; empty: its own
    std::string usage;       // vibscored's usage name: decides arbitration
    double intensity = 1.0;  // 0..1
};

class Theme {
  public:
    std::string name;
    // What was read past (feedbackd reads past it too), each at its file:line:column.
    std::vector<Diagnostic> warnings;

    // What `event` plays in `profile`: the entry of the highest profile up to it that defines
    // the event (a quiet entry plays in full too), or nothing.
    const ThemeEntry* lookup(std::string_view event, Profile profile) const;
    // The profile the entry lookup() finds was defined for.
    std::optional<Profile> level_of(std::string_view event, Profile profile) const;

    void add(Profile profile, const std::string& event, ThemeEntry entry);
    const std::map<std::string, std::map<Profile, ThemeEntry>, std::less<>>& events() const {
        return events_;
    }

  private:
    std::map<std::string, std::map<Profile, ThemeEntry>, std::less<>> events_;
};

// A theme file of either format (told apart by vibscore's "vibscore-theme" key), a feedbackd
// theme with the parents it names found through `search`. Throws DocumentError
// "file:line:column: what" for anything that is not a valid theme.
Theme load_theme(const std::string& path, const ThemeSearch& search);
Theme parse_theme(const JsonDocument& document, const ThemeSearch& search);

// vibscored's usage for an event of a feedbackd theme, which has none: from the event naming
// spec's names (phone-incoming-call: ringtone, alarm-clock-elapsed: alarm, button-*: touch...).
std::string usage_for_event(std::string_view event);

}  // namespace vibscore::feedback
