#pragma once

#include <sys/types.h>

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

// The worker that does callers' document work (parsing, binding, fitting, rendering a Play's
// score) off the bus thread (issue 33, item 1). Bounded: a connection may have a few jobs waiting
// and the whole queue a few hundred; fair: the next job is taken round-robin across users, and
// within a user round-robin across its connections, so one app's flood waits behind its own jobs
// and not another app's, nor another user's.
namespace vibscore::daemon {

class FairWorkQueue {
  public:
    struct Options {
        std::size_t threads = 1;
        std::size_t per_connection = 8;  // jobs waiting or running for one connection
        std::size_t total = 256;         // jobs waiting for everyone
    };

    enum class Pushed { queued, connection_full, queue_full };

    // Starts `options.threads` worker threads.
    explicit FairWorkQueue(const Options& options);
    // Jobs not yet started are dropped (destroyed here, unrun); running ones are waited for.
    ~FairWorkQueue();
    FairWorkQueue(const FairWorkQueue&) = delete;
    FairWorkQueue& operator=(const FairWorkQueue&) = delete;

    // Queues `job` for `connection` of `uid`, or says which bound refused it. A job must not
    // throw (what it throws is logged and dropped) and runs on a worker thread.
    Pushed push(uid_t uid, const std::string& connection, std::function<void()> job);

    // Jobs waiting or running for `connection`.
    std::size_t pending(const std::string& connection) const;
    const Options& options() const { return options_; }

  private:
    struct User {
        uid_t uid;
        // Connections with jobs waiting, in their turn order; their jobs by connection.
        std::deque<std::string> turns;
        std::map<std::string, std::deque<std::function<void()>>> jobs;
    };

    void work();
    // The next job in fair order, taken off the queue; under the lock, with one waiting.
    std::pair<std::string, std::function<void()>> take_next();

    Options options_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<User> users_;                      // users with jobs waiting, in their turn order
    std::map<std::string, std::size_t> pending_;  // by connection: waiting + running
    std::size_t waiting_ = 0;
    bool stopping_ = false;
    std::vector<std::thread> threads_;
};

}  // namespace vibscore::daemon
