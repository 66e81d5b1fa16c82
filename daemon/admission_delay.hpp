#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <unordered_map>

#include <sys/types.h>

namespace vibscore::daemon {

// Refusals answered late (admission by work, docs/daemon.md): a refused request that carried a
// document is answered with its LimitExceeded a while later, one at a time per connection. Every
// refused message of a megabyte has already crossed the bus and been read by the bus thread
// before it could be refused (about a millisecond each), so a caller that waits for its answers,
// as nearly every client does, would otherwise be refused hundreds of times a second and keep
// the bus thread reading its megabytes. A connection that already has a refusal waiting is
// answered at once: the bound on the messages held is one per connection.
class DelayedTasks {
  public:
    using Clock = std::chrono::steady_clock;
    // `post` hands a due task to the thread that must run it (the bus thread's queue).
    explicit DelayedTasks(std::function<void(std::function<void()>)> post);
    // Tasks not yet due are dropped unrun.
    ~DelayedTasks();
    DelayedTasks(const DelayedTasks&) = delete;
    DelayedTasks& operator=(const DelayedTasks&) = delete;

    // Posts `task` at `due`; false (and nothing queued) when `key` already has a task waiting.
    bool add(const std::string& key, Clock::time_point due, std::function<void()> task);
    std::size_t waiting() const;

  private:
    struct Entry {
        std::string key;
        std::function<void()> task;
    };
    void run();

    std::function<void(std::function<void()>)> post_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::multimap<Clock::time_point, Entry> due_;
    std::set<std::string> keys_;
    bool stopping_ = false;
    std::thread thread_;
};

// When a user's refusals are answered: no sooner than `delay` after the refusal, and no closer
// than `spacing` to the user's previous one. One connection waiting for its answer re-sends
// once a `delay`; twenty of one user would re-send twenty times as often, each message a
// megabyte the bus thread reads before it can refuse it. Spacing them by user bounds what the
// user's refused documents cost the bus thread whatever its number of connections.
class RefusalPacing {
  public:
    using Clock = DelayedTasks::Clock;
    RefusalPacing(Clock::duration delay, Clock::duration spacing)
        : delay_(delay), spacing_(spacing) {}

    // When to answer `uid`'s refusal made at `now`; counts it as answered then.
    Clock::time_point due(uid_t uid, Clock::time_point now);
    std::size_t users() const { return next_.size(); }

  private:
    Clock::duration delay_;
    Clock::duration spacing_;
    std::unordered_map<uid_t, Clock::time_point> next_;  // the earliest the next may be answered
};

}  // namespace vibscore::daemon
