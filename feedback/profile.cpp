#include "feedback/profile.hpp"

namespace vibscore::feedback {

std::optional<Profile> parse_profile(std::string_view name) {
    for (const Profile profile : {Profile::silent, Profile::quiet, Profile::full}) {
        if (name == to_string(profile)) {
            return profile;
        }
    }
    return std::nullopt;
}

std::string_view to_string(Profile profile) {
    switch (profile) {
        case Profile::silent:
            return "silent";
        case Profile::quiet:
            return "quiet";
        case Profile::full:
            return "full";
    }
    return "full";
}

}  // namespace vibscore::feedback
