#include "daemon/work_queue.hpp"

#include <algorithm>
#include <exception>
#include <utility>

#include "common/log.hpp"

namespace vibscore::daemon {

FairWorkQueue::FairWorkQueue(const Options& options) : options_(options) {
    for (std::size_t i = 0; i < std::max<std::size_t>(1, options_.threads); ++i) {
        threads_.emplace_back([this] { work(); });
    }
}

FairWorkQueue::~FairWorkQueue() {
    std::deque<User> dropped;
    {
        const std::lock_guard lock(mutex_);
        stopping_ = true;
        dropped.swap(users_);
    }
    wake_.notify_all();
    for (auto& thread : threads_) {
        thread.join();
    }
}

FairWorkQueue::Pushed FairWorkQueue::push(uid_t uid, const std::string& connection,
                                          std::function<void()> job) {
    {
        const std::lock_guard lock(mutex_);
        if (waiting_ >= options_.total) {
            return Pushed::queue_full;
        }
        auto& pending = pending_[connection];
        if (pending >= options_.per_connection) {
            return Pushed::connection_full;
        }
        auto user = std::find_if(users_.begin(), users_.end(),
                                 [uid](const User& each) { return each.uid == uid; });
        if (user == users_.end()) {
            users_.push_back(User{uid, {}, {}});
            user = std::prev(users_.end());
        }
        auto& jobs = user->jobs[connection];
        if (jobs.empty()) {
            user->turns.push_back(connection);
        }
        jobs.push_back(std::move(job));
        ++pending;
        ++waiting_;
    }
    wake_.notify_one();
    return Pushed::queued;
}

std::size_t FairWorkQueue::pending(const std::string& connection) const {
    const std::lock_guard lock(mutex_);
    const auto found = pending_.find(connection);
    return found == pending_.end() ? 0 : found->second;
}

std::pair<std::string, std::function<void()>> FairWorkQueue::take_next() {
    User user = std::move(users_.front());
    users_.pop_front();
    std::string connection = std::move(user.turns.front());
    user.turns.pop_front();
    auto& jobs = user.jobs.at(connection);
    auto job = std::move(jobs.front());
    jobs.pop_front();
    if (jobs.empty()) {
        user.jobs.erase(connection);
    } else {
        user.turns.push_back(connection);  // its next job after the user's other connections'
    }
    if (!user.turns.empty()) {
        users_.push_back(std::move(user));  // its next turn after every other user's
    }
    --waiting_;
    return {std::move(connection), std::move(job)};
}

void FairWorkQueue::work() {
    for (;;) {
        std::pair<std::string, std::function<void()>> next;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || !users_.empty(); });
            if (stopping_) {
                return;
            }
            next = take_next();
        }
        try {
            next.second();
        } catch (const std::exception& error) {
            log::error("a worker's job failed: " + std::string(error.what()));
        } catch (...) {
            log::error("a worker's job failed with an unknown exception");
        }
        next.second = nullptr;  // what the job held goes before it counts as done
        const std::lock_guard lock(mutex_);
        const auto found = pending_.find(next.first);
        if (found != pending_.end() && --found->second == 0) {
            pending_.erase(found);
        }
    }
}

}  // namespace vibscore::daemon
