#pragma once

#include <sys/types.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "common/usage.hpp"

namespace vibscore::daemon {

// How long one playback may hold the actuator, and how long a user who was cut off waits before
// taking it again with a repeating playback: the daemon is shared, so no one caller's playback
// may keep every equally important one-shot of everyone else out (issue 33, row 2), and a
// fire-and-forget one-shot whose caller has gone is bounded like any other (row 3).
// vibscored.conf [limits]; docs/daemon.md, Limits.
inline constexpr std::size_t kUsageCount = static_cast<std::size_t>(Usage::media) + 1;
inline constexpr double kDefaultMaxOnTime_s = 30.0;
inline constexpr double kDefaultCoolDown_s = 10.0;
// The largest values the configuration takes: a limit beyond a day is no limit one could test,
// and a cool-down beyond an hour would make the daemon's memory of who was cut off unbounded in
// time.
inline constexpr double kLongestMaxOnTime_s = 86'400.0;
inline constexpr double kLongestCoolDown_s = 3'600.0;

class PlaybackLimits {
  public:
    // Until stopped (nullopt) for the urgent usages (ringtone, alarm), which need
    // org.vibscore.urgent-usage; `default_max_on_time_s` for every other usage.
    std::optional<double> max_on_time(Usage usage) const;
    double cool_down_s() const { return cool_down_s_; }

    // One [limits] key: "max-on-time" (every non-urgent usage), "max-on-time-USAGE" (that usage
    // only, urgent ones too; it wins over max-on-time whatever the order of the lines) or
    // "cool-down". A max-on-time is seconds above 0 or "none" (until stopped); a cool-down is
    // seconds, 0 for none. Throws std::invalid_argument naming the key and the value.
    void set(const std::string& key, const std::string& value);

  private:
    std::optional<double> non_urgent_s_ = kDefaultMaxOnTime_s;
    std::array<std::optional<std::optional<double>>, kUsageCount> by_usage_{};
    double cool_down_s_ = kDefaultCoolDown_s;
};

// When a playback that began at `start_us` reaches its maximum on-time (nullopt: never). Counted
// from its start across every repeat, so re-passing the score cannot renew it.
std::optional<std::uint64_t> max_on_time_deadline_us(std::uint64_t start_us,
                                                     std::optional<double> max_on_time_s);

// What the player does next with a playback whose next cue is due at `next_due_us`, at `now_us`:
// every cue due up to and including the deadline runs (a score exactly as long as the limit
// completes); once the deadline has come with cues still left, the playback ends.
struct NextStep {
    enum class Kind { run_cue, wait, end_over_limit } kind;
    std::uint64_t wake_us = 0;  // for wait
};
NextStep next_step(std::uint64_t now_us, std::uint64_t next_due_us,
                   std::optional<std::uint64_t> deadline_us);

// The reason a playback cut off at its maximum on-time finishes with (PlaybackFinished).
std::string over_on_time_reason(double max_on_time_s);
// Whether `reason` is that one (and not another "limit-exceeded: ...").
bool is_over_on_time(const std::string& reason);

// A request refused because its user is cooling down: the Play error CoolingDown.
class CoolingDown : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Who was cut off when: a user whose playback reached its maximum on-time or was ended by an
// administrator's StopAll may start no repeating playback of a non-urgent usage for the
// cool-down. One-shots stay allowed (each is bounded by its maximum on-time and yields to an
// equally important request), and so do the urgent usages, which need polkit's
// org.vibscore.urgent-usage anyway. Arbitration between usages is not touched.
class CoolDowns {
  public:
    void cut_off(uid_t uid, std::uint64_t now_us);
    // How long `uid` must still wait before starting a playback of `usage` that repeats
    // `repeat` times more; 0: it may start now.
    std::uint64_t wait_us(uid_t uid, Usage usage, int repeat, double cool_down_s,
                          std::uint64_t now_us) const;
    // Throws CoolingDown naming the user, the time left and the key when wait_us() is not 0.
    void check(uid_t uid, Usage usage, int repeat, double cool_down_s, std::uint64_t now_us) const;
    std::size_t remembered() const { return since_us_.size(); }

  private:
    std::unordered_map<uid_t, std::uint64_t> since_us_;
};

}  // namespace vibscore::daemon
