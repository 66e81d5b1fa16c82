#include "daemon/playback_positions.hpp"

#include <algorithm>

namespace vibscore::daemon {

namespace {

constexpr std::uint64_t cost_us(std::uint64_t rate) {
    return 1'000'000 / rate;
}

}  // namespace

PositionBudget::Bucket PositionBudget::fresh(std::uint64_t rate, std::uint64_t burst,
                                             std::uint64_t now_us) {
    return {cost_us(rate) * burst, now_us};
}

std::uint64_t PositionBudget::credit(const Bucket& bucket, std::uint64_t rate, std::uint64_t burst,
                                     std::uint64_t now_us) {
    const std::uint64_t full = cost_us(rate) * burst;
    const std::uint64_t earned = now_us > bucket.at_us ? now_us - bucket.at_us : 0;
    return std::min(full, bucket.credit_us + earned);
}

std::uint64_t PositionBudget::ready_at(const Bucket& bucket, std::uint64_t rate,
                                       std::uint64_t burst, std::uint64_t now_us) {
    const std::uint64_t have = credit(bucket, rate, burst, now_us);
    return have >= cost_us(rate) ? now_us : now_us + (cost_us(rate) - have);
}

std::uint64_t PositionBudget::available_at(const std::string& sender, std::uint64_t now_us) const {
    std::uint64_t at = now_us;
    if (total_) {
        at = std::max(at,
                      ready_at(*total_, kPositionsPerSecondInTotal, kPositionBurstInTotal, now_us));
    }
    if (const auto found = senders_.find(sender); found != senders_.end()) {
        at = std::max(at, ready_at(found->second, kPositionsPerSecondPerConnection,
                                   kPositionBurstPerConnection, now_us));
    }
    return at;
}

bool PositionBudget::take(const std::string& sender, std::uint64_t now_us) {
    constexpr std::uint64_t kRate = kPositionsPerSecondPerConnection;
    constexpr std::uint64_t kBurst = kPositionBurstPerConnection;
    if (available_at(sender, now_us) > now_us) {
        return false;
    }
    std::erase_if(senders_, [&](const auto& entry) {
        return entry.first != sender &&
               credit(entry.second, kRate, kBurst, now_us) == cost_us(kRate) * kBurst;
    });
    Bucket total =
        total_.value_or(fresh(kPositionsPerSecondInTotal, kPositionBurstInTotal, now_us));
    total_ = Bucket{credit(total, kPositionsPerSecondInTotal, kPositionBurstInTotal, now_us) -
                        cost_us(kPositionsPerSecondInTotal),
                    now_us};
    const auto found = senders_.find(sender);
    const Bucket own = found != senders_.end() ? found->second : fresh(kRate, kBurst, now_us);
    senders_[sender] = Bucket{credit(own, kRate, kBurst, now_us) - cost_us(kRate), now_us};
    return true;
}

}  // namespace vibscore::daemon
