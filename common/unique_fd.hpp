#pragma once

#include <unistd.h>

#include <cerrno>
#include <utility>

namespace vibscore {

// Owns one file descriptor and closes it exactly once, on every path out of its scope.
class UniqueFd {
  public:
    explicit UniqueFd(int fd = -1) noexcept : fd_(fd) {}
    UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
    UniqueFd& operator=(UniqueFd&& other) noexcept {
        if (this != &other) {
            close();
            fd_ = std::exchange(other.fd_, -1);
        }
        return *this;
    }
    UniqueFd(const UniqueFd&) = delete;
    UniqueFd& operator=(const UniqueFd&) = delete;
    ~UniqueFd() { close(); }

    int get() const noexcept { return fd_; }

    // Closes now and returns 0 or close()'s errno, which a destructor cannot report. EINTR counts
    // as closed: Linux releases the descriptor even then, so it is never retried.
    int close() noexcept {
        if (fd_ < 0) {
            return 0;
        }
        const int result = ::close(std::exchange(fd_, -1));
        return result != 0 && errno != EINTR ? errno : 0;
    }

  private:
    int fd_;
};

}  // namespace vibscore
