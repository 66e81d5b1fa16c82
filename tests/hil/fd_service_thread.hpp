#pragma once

#include <functional>
#include <thread>

#include "common/unique_fd.hpp"

namespace vibscore::hil {

// A thread that waits on one file descriptor and calls `on_readable` whenever it can be read,
// until this is destroyed. The fixtures answer the kernel from such a thread, so a test blocked
// in a system call that waits for them (closing an evdev fd waits for uinput's erase answer)
// cannot deadlock. An exception from `on_readable` ends the test program with its message: a
// fixture that stopped answering would only turn into a confusing timeout later.
class FdServiceThread {
  public:
    FdServiceThread(int fd, std::function<void()> on_readable);
    ~FdServiceThread();
    FdServiceThread(const FdServiceThread&) = delete;
    FdServiceThread& operator=(const FdServiceThread&) = delete;

  private:
    void run(int fd, const std::function<void()>& on_readable) const;

    UniqueFd stop_;  // an eventfd: readable once the destructor wants the thread to end
    std::thread thread_;
};

}  // namespace vibscore::hil
