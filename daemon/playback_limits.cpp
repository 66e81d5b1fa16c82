#include "daemon/playback_limits.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>

#include "common/ini_reader.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"
#include "daemon/authority.hpp"

namespace vibscore::daemon {

namespace {

constexpr std::string_view kMaxOnTimeKey = "max-on-time";
constexpr std::string_view kCoolDownKey = "cool-down";

std::uint64_t to_us(double seconds) {
    return static_cast<std::uint64_t>(std::llround(seconds * 1e6));
}

// Seconds from `lowest` (itself allowed only when `zero_allowed`) to `highest`; nullopt when the
// text is not such a number.
std::optional<double> seconds(const std::string& value, bool zero_allowed, double highest) {
    const auto parsed = ini_number(value);
    if (!parsed) {
        return std::nullopt;
    }
    const double number = *parsed;
    if (number < 0.0 || (number == 0.0 && !zero_allowed) || number > highest) {
        return std::nullopt;
    }
    // Below a microsecond, the player's clock could not tell the limit from none.
    if (number != 0.0 && number < 1e-6) {
        return std::nullopt;
    }
    return number;
}

std::optional<double> max_on_time_value(const std::string& key, const std::string& value) {
    if (value == "none") {
        return std::nullopt;
    }
    const auto number = seconds(value, false, kLongestMaxOnTime_s);
    if (!number) {
        throw std::invalid_argument(key + " = " + quoted_text(value) +
                                    " is neither \"none\" nor seconds from 0.000001 to " +
                                    number_text(kLongestMaxOnTime_s));
    }
    return number;
}

}  // namespace

std::optional<double> PlaybackLimits::max_on_time(Usage usage) const {
    if (const auto& own = by_usage_.at(static_cast<std::size_t>(usage))) {
        return *own;
    }
    return needs_urgent_usage(usage) ? std::nullopt : non_urgent_s_;
}

void PlaybackLimits::set(const std::string& key, const std::string& value) {
    if (key == kMaxOnTimeKey) {
        non_urgent_s_ = max_on_time_value(key, value);
        return;
    }
    if (key == kCoolDownKey) {
        const auto number = seconds(value, true, kLongestCoolDown_s);
        if (!number) {
            throw std::invalid_argument(key + " = " + quoted_text(value) +
                                        " is not seconds from 0 (none) to " +
                                        number_text(kLongestCoolDown_s));
        }
        cool_down_s_ = *number;
        return;
    }
    const std::string prefix = std::string(kMaxOnTimeKey) + "-";
    if (key.starts_with(prefix)) {
        if (const auto usage = parse_usage(std::string_view(key).substr(prefix.size()))) {
            by_usage_.at(static_cast<std::size_t>(*usage)) = max_on_time_value(key, value);
            return;
        }
    }
    throw std::invalid_argument("unknown key " + quoted_text(key) +
                                " in [limits] (expected max-on-time, cool-down or "
                                "max-on-time-USAGE, USAGE one of " +
                                std::string(usage_names()) + ")");
}

std::optional<std::uint64_t> max_on_time_deadline_us(std::uint64_t start_us,
                                                     std::optional<double> max_on_time_s) {
    if (!max_on_time_s) {
        return std::nullopt;
    }
    return start_us + to_us(*max_on_time_s);
}

NextStep next_step(std::uint64_t now_us, std::uint64_t next_due_us,
                   std::optional<std::uint64_t> deadline_us) {
    if (deadline_us && next_due_us > *deadline_us && now_us >= *deadline_us) {
        return {NextStep::Kind::end_over_limit};
    }
    if (next_due_us <= now_us) {
        return {NextStep::Kind::run_cue};
    }
    std::uint64_t wake = next_due_us;
    if (deadline_us) {
        wake = std::min(wake, *deadline_us);
    }
    return {NextStep::Kind::wait, wake};
}

namespace {
constexpr std::string_view kOverOnTime = "limit-exceeded: played for its maximum on-time of ";
}

std::string over_on_time_reason(double max_on_time_s) {
    return std::string(kOverOnTime) + number_text(max_on_time_s) + " s ([limits] max-on-time)";
}

bool is_over_on_time(const std::string& reason) {
    return reason.starts_with(kOverOnTime);
}

void CoolDowns::cut_off(uid_t uid, std::uint64_t now_us) {
    // Whoever was cut off more than the longest cool-down ago is forgotten, so the memory is
    // bounded by the users cut off within the last hour.
    const std::uint64_t longest = to_us(kLongestCoolDown_s);
    std::erase_if(since_us_, [&](const auto& entry) { return entry.second + longest <= now_us; });
    since_us_[uid] = now_us;
}

std::uint64_t CoolDowns::wait_us(uid_t uid, Usage usage, int repeat, double cool_down_s,
                                 std::uint64_t now_us) const {
    if (repeat == 0 || needs_urgent_usage(usage)) {
        return 0;
    }
    const auto found = since_us_.find(uid);
    if (found == since_us_.end()) {
        return 0;
    }
    const std::uint64_t until = found->second + to_us(cool_down_s);
    return until > now_us ? until - now_us : 0;
}

void CoolDowns::check(uid_t uid, Usage usage, int repeat, double cool_down_s,
                      std::uint64_t now_us) const {
    const std::uint64_t wait = wait_us(uid, usage, repeat, cool_down_s, now_us);
    if (wait == 0) {
        return;
    }
    throw CoolingDown("uid " + std::to_string(uid) +
                      " had a playback cut off (maximum on-time or StopAll) and may start no "
                      "repeating " +
                      std::string(to_string(usage)) + " playback for another " +
                      number_text(static_cast<double>(wait) / 1e6) + " s ([limits] cool-down = " +
                      number_text(cool_down_s) + " s); a one-shot may play meanwhile");
}

}  // namespace vibscore::daemon
