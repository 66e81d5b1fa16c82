#pragma once

#include <optional>
#include <string_view>

namespace vibscore::feedback {

// feedbackd's feedback profiles, in order: a profile gives the feedback its theme defines for
// it and for every lower one (full: sound, vibration and LEDs; quiet: vibration and LEDs;
// silent: LEDs only, so nothing here).
enum class Profile { silent, quiet, full };

std::optional<Profile> parse_profile(std::string_view name);
std::string_view to_string(Profile profile);
inline constexpr std::string_view kProfileNames = "full, quiet or silent";

}  // namespace vibscore::feedback
