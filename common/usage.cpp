#include "common/usage.hpp"

#include <array>
#include <utility>

namespace vibscore::daemon {

namespace {

struct UsageInfo {
    Usage usage;
    std::string_view name;
    int importance;
};

constexpr std::array<UsageInfo, 8> kUsages{{
    {Usage::ringtone, "ringtone", 6},
    {Usage::alarm, "alarm", 5},
    {Usage::notification, "notification", 4},
    {Usage::communication, "communication", 3},
    {Usage::accessibility, "accessibility", 3},
    {Usage::hardware_feedback, "hardware-feedback", 2},
    {Usage::touch, "touch", 1},
    {Usage::media, "media", 1},
}};

const UsageInfo& info(Usage usage) {
    return kUsages.at(static_cast<std::size_t>(usage));
}

}  // namespace

std::optional<Usage> parse_usage(std::string_view name) {
    for (const auto& each : kUsages) {
        if (each.name == name) {
            return each.usage;
        }
    }
    return std::nullopt;
}

std::string_view to_string(Usage usage) {
    return info(usage).name;
}

std::string_view usage_names() {
    return "ringtone, alarm, notification, communication, accessibility, hardware-feedback, "
           "touch, media";
}

int importance(Usage usage) {
    return info(usage).importance;
}

}  // namespace vibscore::daemon
