#pragma once

#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/unique_fd.hpp"

namespace vibscore::daemon {

// Tasks one thread hands another: push() from any thread; the receiving thread watches fd() in
// its loop and runs what was pushed with run_all(), in order.
class TaskQueue {
  public:
    TaskQueue() : ready_(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK)) {
        if (ready_.get() < 0) {
            throw std::runtime_error(std::string("eventfd: ") + std::strerror(errno));
        }
    }

    // Readable while tasks wait.
    int fd() const { return ready_.get(); }

    void push(std::function<void()> task) {
        {
            const std::lock_guard lock(mutex_);
            tasks_.push_back(std::move(task));
        }
        const std::uint64_t one = 1;
        // The counter only has to be non-zero; a full counter (EAGAIN) is as good as a write.
        [[maybe_unused]] const auto written = ::write(ready_.get(), &one, sizeof one);
    }

    // Runs the tasks pushed so far (a task may push more; they run in a later call).
    void run_all() {
        std::uint64_t count = 0;
        [[maybe_unused]] const auto read = ::read(ready_.get(), &count, sizeof count);
        std::vector<std::function<void()>> tasks;
        {
            const std::lock_guard lock(mutex_);
            tasks.swap(tasks_);
        }
        for (auto& task : tasks) {
            task();
        }
    }

  private:
    UniqueFd ready_;
    std::mutex mutex_;
    std::vector<std::function<void()>> tasks_;
};

}  // namespace vibscore::daemon
