#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "feedback/json_fields.hpp"
#include "feedback/profile.hpp"
#include "feedback/theme.hpp"
#include "feedback/vibra_feedback.hpp"
#include "score/document_error.hpp"

// feedbackd's theme JSON (/usr/share/feedbackd/themes/default.json, 0.0.3's and 0.8's) read as
// feedbackd 0.8.2 reads it (fbd-feedback-theme.c, fbd-feedback-profile.c, fbd-theme-expander.c):
// its VibraRumble, VibraPeriodic and VibraPattern entries become the vibra feedbacks feedbackd
// plays; Sound, Led and Dummy entries give no vibration. What feedbackd reads past is read past
// with a warning that names the place, so a theme written for a newer feedbackd still loads: an
// unknown feedback type, profile or member; magnitudes of the old 0..0x7fff scale (converted);
// a value outside its property's range (feedbackd keeps the default). The structure is checked
// strictly: a theme whose shape feedbackd cannot use is an error at its file:line:column.
namespace vibscore::feedback {

// One theme file as read, before its parents are merged in.
struct FeedbackdThemeFile {
    std::string path;
    std::string name;
    std::optional<std::string> parent_name;
    SourceLocation name_at;  // the file, when it has no name
    SourceLocation parent_at;
    // Per profile, the feedback of each event: the last one the file gives (feedbackd keeps one
    // per event and profile), or nothing when it does not vibrate, which hides a parent's vibra
    // feedback for the same event and profile as in feedbackd.
    std::map<Profile, std::map<std::string, std::optional<VibraFeedback>>> profiles;
    std::vector<Diagnostic> warnings;
};

// Throws DocumentError "file:line:column: what".
FeedbackdThemeFile read_feedbackd_theme_file(const JsonFields& json);

// Where feedbackd 0.8 looks for a theme by name (a parent-name): the user's
// config_home/feedbackd/themes/NAME.json; for "default" and "$device", once per chain, the
// device's own theme DIR/feedbackd/themes/COMPATIBLE.json; then the default theme
// DIR/feedbackd/themes/default.json (any other name falls back to it, with a warning); last,
// builtin_dir/NAME.json.
struct ThemeSearch {
    std::filesystem::path config_home;
    std::vector<std::filesystem::path> data_dirs;
    std::vector<std::string> compatibles;  // the device tree's, most specific first
    std::filesystem::path builtin_dir = "/usr/share/feedbackd/themes";

    // $XDG_CONFIG_HOME (else ~/.config), $XDG_DATA_DIRS (else /usr/local/share:/usr/share), and
    // /sys/firmware/devicetree/base/compatible, as feedbackd finds them.
    static ThemeSearch from_environment();
    // The file feedbackd would read for `name`. `device_theme_tried` is the chain's: the
    // device theme is looked for once.
    std::filesystem::path find(const std::string& name, bool& device_theme_tried,
                               std::vector<Diagnostic>& warnings) const;
};

// A chain of a theme and its parents longer than this is refused (feedbackd's
// MAX_THEME_DEPTH).
inline constexpr std::size_t kMaxParentThemes = 10;

// `file` with its parents merged in, the deepest first, each file's feedbacks replacing its
// parent's for the same event and profile. Errors as feedbackd's: an empty name, the default
// theme naming a parent, more than kMaxParentThemes parents; and a parent that cannot be read.
Theme expand_feedbackd_theme(FeedbackdThemeFile file, const ThemeSearch& search);

// The event's vibra feedback as a theme entry (usage from the event's name).
ThemeEntry vibra_entry(const std::string& event, VibraFeedback feedback);

}  // namespace vibscore::feedback
