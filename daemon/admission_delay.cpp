#include "daemon/admission_delay.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace vibscore::daemon {

DelayedTasks::DelayedTasks(std::function<void(std::function<void()>)> post)
    : post_(std::move(post)), thread_([this] { run(); }) {}

DelayedTasks::~DelayedTasks() {
    {
        const std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

bool DelayedTasks::add(const std::string& key, Clock::time_point due, std::function<void()> task) {
    {
        const std::lock_guard lock(mutex_);
        if (stopping_ || !keys_.insert(key).second) {
            return false;
        }
        due_.emplace(due, Entry{key, std::move(task)});
    }
    wake_.notify_all();
    return true;
}

std::size_t DelayedTasks::waiting() const {
    const std::lock_guard lock(mutex_);
    return due_.size();
}

void DelayedTasks::run() {
    std::unique_lock lock(mutex_);
    while (!stopping_) {
        if (due_.empty()) {
            wake_.wait(lock);
            continue;
        }
        const auto next = due_.begin()->first;
        if (Clock::now() < next) {
            wake_.wait_until(lock, next);
            continue;
        }
        std::vector<std::function<void()>> ready;
        while (!due_.empty() && due_.begin()->first <= Clock::now()) {
            keys_.erase(due_.begin()->second.key);
            ready.push_back(std::move(due_.begin()->second.task));
            due_.erase(due_.begin());
        }
        lock.unlock();
        for (auto& task : ready) {
            post_(std::move(task));
        }
        lock.lock();
    }
    // Tasks not yet due stay in due_, destroyed with it by the destructor's thread.
}

RefusalPacing::Clock::time_point RefusalPacing::due(uid_t uid, Clock::time_point now) {
    // Users whose pacing has run out are forgotten, so the map holds only recent refusers.
    if (next_.size() > 64) {
        std::erase_if(next_, [now](const auto& entry) { return entry.second <= now; });
    }
    const auto [found, fresh] = next_.try_emplace(uid, now);
    const Clock::time_point at = std::max(now + delay_, found->second);
    found->second = at + spacing_;
    return at;
}

}  // namespace vibscore::daemon
