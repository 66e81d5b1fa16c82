#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>

namespace vibscore::daemon {

// PlaybackPosition is a broadcast: every client that listens receives every one. Bounded per
// playback only, a stream of short Plays sent 111 positions a second (issue 33, row 4): each
// new playback began with a fresh interval. So positions are also bounded per bus connection
// that started the playbacks, across all of them, and bus-wide: token buckets, refilled at the
// rate and holding a small burst, so that a playback's last position (reported as it ends) still
// fits after a steady 50 a second. A position over either bound is held (the latest replaces it)
// and reported once the budget allows, or dropped when its playback ends first; PlaybackFinished
// is never held back.
inline constexpr std::uint64_t kPositionsPerSecondPerConnection = 50;
inline constexpr std::uint64_t kPositionBurstPerConnection = 2;
inline constexpr std::uint64_t kPositionsPerSecondInTotal = 100;
inline constexpr std::uint64_t kPositionBurstInTotal = 4;

class PositionBudget {
  public:
    // When a position of a playback `sender` started may be reported: `now_us` when it may now.
    std::uint64_t available_at(const std::string& sender, std::uint64_t now_us) const;
    // Spends one report for `sender` at `now_us`; false, spending nothing, when over either
    // bound.
    bool take(const std::string& sender, std::uint64_t now_us);
    // Connections with a budget that is not full; the others are forgotten (a full bucket is a
    // fresh one), so this stays as small as the connections reporting within a few dozen ms.
    std::size_t remembered() const { return senders_.size(); }

  private:
    // Credit in microseconds of the bucket's own time: a report costs 1 s / rate.
    struct Bucket {
        std::uint64_t credit_us;
        std::uint64_t at_us;
    };
    static Bucket fresh(std::uint64_t rate, std::uint64_t burst, std::uint64_t now_us);
    static std::uint64_t credit(const Bucket& bucket, std::uint64_t rate, std::uint64_t burst,
                                std::uint64_t now_us);
    static std::uint64_t ready_at(const Bucket& bucket, std::uint64_t rate, std::uint64_t burst,
                                  std::uint64_t now_us);

    std::optional<Bucket> total_;
    std::unordered_map<std::string, Bucket> senders_;
};

}  // namespace vibscore::daemon
