#include "feedback/user_scores_writer.hpp"

#include <sys/epoll.h>
#include <sys/eventfd.h>

#include <cerrno>
#include <cstdint>
#include <string>
#include <system_error>
#include <utility>

#include "common/log.hpp"
#include "feedback/user_scores.hpp"

namespace vibscore::feedback {

UserScoresWriter::UserScoresWriter(daemon::EventLoop& loop, std::filesystem::path file)
    : file_(std::move(file)), wake_(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK)) {
    if (wake_.get() < 0) {
        throw std::system_error(errno, std::generic_category(),
                                "cannot make an eventfd to store " + file_.string());
    }
    sd_event_source* source = nullptr;
    const int result = sd_event_add_io(loop.get(), &source, wake_.get(), EPOLLIN,
                                       &UserScoresWriter::on_wake, this);
    if (result < 0) {
        throw std::system_error(-result, std::generic_category(),
                                "cannot watch the eventfd that stores " + file_.string());
    }
    source_.reset(source);
    thread_ = std::thread([this] { run(); });
}

UserScoresWriter::~UserScoresWriter() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    work_.notify_one();
    thread_.join();
}

bool UserScoresWriter::submit(std::string event, std::string score, Done done) {
    {
        std::lock_guard lock(mutex_);
        if (waiting_.size() >= kMaxWaiting) {
            return false;
        }
        waiting_.push_back({std::move(event), std::move(score), std::move(done)});
    }
    work_.notify_one();
    return true;
}

void UserScoresWriter::run() {
    std::unique_lock lock(mutex_);
    for (;;) {
        work_.wait(lock, [this] { return stopping_ || !waiting_.empty(); });
        if (waiting_.empty()) {
            return;  // stopping, and every queued store is done
        }
        Job job = std::move(waiting_.front());
        waiting_.pop_front();
        lock.unlock();
        std::exception_ptr error;
        try {
            store_user_score(file_, job.event, job.score);
        } catch (...) {
            error = std::current_exception();
        }
        lock.lock();
        finished_.push_back({std::move(job.done), error});
        const std::uint64_t one = 1;
        // An eventfd's counter only fails to take 1 at 2^64 - 2, never reached here.
        [[maybe_unused]] const auto written = ::write(wake_.get(), &one, sizeof one);
    }
}

int UserScoresWriter::on_wake(sd_event_source*, int fd, std::uint32_t, void* self) {
    auto* writer = static_cast<UserScoresWriter*>(self);
    std::uint64_t count = 0;
    [[maybe_unused]] const auto read = ::read(fd, &count, sizeof count);
    std::deque<Outcome> outcomes;
    {
        std::lock_guard lock(writer->mutex_);
        outcomes.swap(writer->finished_);
    }
    for (auto& outcome : outcomes) {
        // Nothing may leave through sd-event's C frames; a reply that cannot be sent (the
        // caller left) must not cost the others theirs.
        try {
            outcome.done(outcome.error);
        } catch (const std::exception& error) {
            log::warning(std::string("after storing a choice: ") + error.what());
        }
    }
    return 0;
}

}  // namespace vibscore::feedback
