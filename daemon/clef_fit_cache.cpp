#include "daemon/clef_fit_cache.hpp"

#include <algorithm>

namespace vibscore::daemon {

Clef ClefFitCache::fitted(const std::string& name, const Clef& written,
                          const actuator::Declaration& actuator,
                          const std::function<Clef(const Clef&)>& fit) {
    {
        const std::lock_guard lock(mutex_);
        if (actuator_ == actuator) {
            const auto found = by_name_.find(name);
            if (found != by_name_.end()) {
                const auto& entries = found->second;
                const auto entry =
                    std::find_if(entries.begin(), entries.end(),
                                 [&](const Entry& each) { return each.written == written; });
                if (entry != entries.end()) {
                    return entry->fitted;
                }
            }
        }
    }
    // Fitted outside the lock: another worker's lookups do not wait for it. Two workers missing
    // the same clef at once both fit it; the second entry is not added.
    Clef result = fit(written);
    const std::lock_guard lock(mutex_);
    ++fits_;
    if (actuator_ != actuator || size_ >= kMaxEntries) {
        by_name_.clear();
        size_ = 0;
        actuator_ = actuator;
    }
    auto& entries = by_name_[name];
    if (std::none_of(entries.begin(), entries.end(),
                     [&](const Entry& each) { return each.written == written; })) {
        entries.push_back({written, result});
        ++size_;
    }
    return result;
}

void ClefFitCache::clear() {
    const std::lock_guard lock(mutex_);
    by_name_.clear();
    size_ = 0;
    actuator_.reset();
}

std::size_t ClefFitCache::size() const {
    const std::lock_guard lock(mutex_);
    return size_;
}

std::size_t ClefFitCache::fits() const {
    const std::lock_guard lock(mutex_);
    return fits_;
}

}  // namespace vibscore::daemon
