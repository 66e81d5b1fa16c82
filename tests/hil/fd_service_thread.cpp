#include "tests/hil/fd_service_thread.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <system_error>

namespace vibscore::hil {

FdServiceThread::FdServiceThread(int fd, std::function<void()> on_readable)
    : stop_(::eventfd(0, EFD_CLOEXEC)) {
    if (stop_.get() < 0) {
        throw std::system_error(errno, std::generic_category(), "eventfd");
    }
    thread_ = std::thread([this, fd, on_readable = std::move(on_readable)] {
        try {
            run(fd, on_readable);
        } catch (const std::exception& error) {
            std::fprintf(stderr, "hil fixture thread failed: %s\n", error.what());
            std::abort();
        }
    });
}

FdServiceThread::~FdServiceThread() {
    const std::uint64_t one = 1;
    if (::write(stop_.get(), &one, sizeof one) != sizeof one) {
        std::perror("hil fixture: cannot stop the service thread");
        std::abort();
    }
    thread_.join();
}

void FdServiceThread::run(int fd, const std::function<void()>& on_readable) const {
    for (;;) {
        pollfd fds[2] = {{fd, POLLIN, 0}, {stop_.get(), POLLIN, 0}};
        if (::poll(fds, 2, -1) < 0) {
            if (errno == EINTR) {
                continue;
            }
            throw std::system_error(errno, std::generic_category(), "poll");
        }
        if (fds[1].revents != 0) {
            return;
        }
        if ((fds[0].revents & (POLLERR | POLLHUP | POLLNVAL)) != 0) {
            return;
        }
        if ((fds[0].revents & POLLIN) != 0) {
            on_readable();
        }
    }
}

}  // namespace vibscore::hil
