#pragma once

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/unique_fd.hpp"
#include "tests/hil/fd_service_thread.hpp"

namespace vibscore::hil {

struct WrittenValue {
    std::chrono::steady_clock::time_point time;  // when the fixture read it (CLOCK_MONOTONIC)
    std::string value;
};

// A regular file standing in for a sysfs attribute that no kernel driver provides (Android's
// timed_output): it records every value a writer leaves in it, i.e. the content after each
// open-write-close (inotify IN_CLOSE_WRITE), read from its own thread. Writes closer together
// than that thread reads can merge: use intervals of milliseconds.
class WrittenFile {
  public:
    WrittenFile(const std::filesystem::path& path, const std::string& initial);
    ~WrittenFile();
    WrittenFile(const WrittenFile&) = delete;
    WrittenFile& operator=(const WrittenFile&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::vector<WrittenValue> writes() const;
    // Waits until a recorded write matches `match`; false after `timeout`.
    bool wait_for(const std::function<bool(const WrittenValue&)>& match,
                  std::chrono::milliseconds timeout = std::chrono::seconds(5)) const;

  private:
    void service();  // runs on the service thread

    std::filesystem::path path_;
    UniqueFd inotify_;
    mutable std::mutex mutex_;  // guards what follows
    mutable std::condition_variable changed_;
    std::vector<WrittenValue> writes_;
    std::unique_ptr<FdServiceThread> thread_;  // last: stops before the rest goes
};

}  // namespace vibscore::hil
