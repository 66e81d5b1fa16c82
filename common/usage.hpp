#pragma once

#include <optional>
#include <string_view>

namespace vibscore::daemon {

// Why something vibrates. Decides which of two overlapping playbacks wins, as Android does.
enum class Usage {
    ringtone,
    alarm,
    notification,
    communication,
    accessibility,
    hardware_feedback,
    touch,
    media,
};

std::optional<Usage> parse_usage(std::string_view name);
std::string_view to_string(Usage usage);
std::string_view usage_names();  // for error messages

// ringtone > alarm > notification > communication = accessibility > hardware-feedback >
// touch = media.
int importance(Usage usage);

}  // namespace vibscore::daemon
