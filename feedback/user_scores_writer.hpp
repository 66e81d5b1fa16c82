#pragma once

#include <systemd/sd-event.h>

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "common/event_loop.hpp"
#include "common/unique_fd.hpp"

namespace vibscore::feedback {

// Stores the user's choices (store_user_score) on a thread of its own, one at a time in the
// order asked, and tells each caller the outcome back on `loop`'s thread. A store reads the
// file, writes a new one and fsyncs it: tens of milliseconds on a busy flash disk, seconds at
// worst, which must not hold up another app's TriggerFeedback on the bus thread.
class UserScoresWriter {
  public:
    // Stores queued and not yet taken; more are refused (submit() returns false), so that one
    // app calling AssignScore in a loop cannot make the queue grow without end.
    static constexpr std::size_t kMaxWaiting = 32;

    // Called on the loop's thread: nullptr when stored, else what store_user_score threw.
    using Done = std::function<void(std::exception_ptr)>;

    // Throws std::system_error when the loop cannot watch the thread's wake-up.
    UserScoresWriter(daemon::EventLoop& loop, std::filesystem::path file);
    // Finishes the stores already queued (a choice the caller was told nothing about yet is
    // still kept), then stops the thread; their Done is not called.
    ~UserScoresWriter();
    UserScoresWriter(const UserScoresWriter&) = delete;
    UserScoresWriter& operator=(const UserScoresWriter&) = delete;

    // Queues the store of `score` for `event` ("" gives it back to the theme). False, and
    // nothing queued, when kMaxWaiting stores wait already.
    bool submit(std::string event, std::string score, Done done);

  private:
    struct Job {
        std::string event;
        std::string score;
        Done done;
    };
    struct Outcome {
        Done done;
        std::exception_ptr error;
    };

    void run();
    static int on_wake(sd_event_source* source, int fd, std::uint32_t events, void* self);

    std::filesystem::path file_;
    UniqueFd wake_;  // eventfd: the thread's "outcomes are ready" to the loop
    daemon::EventSourcePtr source_;
    std::mutex mutex_;
    std::condition_variable work_;
    std::deque<Job> waiting_;
    std::deque<Outcome> finished_;
    bool stopping_ = false;
    std::thread thread_;  // last: it starts once everything it uses is made
};

}  // namespace vibscore::feedback
