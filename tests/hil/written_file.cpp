#include "tests/hil/written_file.hpp"

#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <stdexcept>

#include "tests/hil/kernel_files.hpp"

namespace vibscore::hil {

WrittenFile::WrittenFile(const std::filesystem::path& path, const std::string& initial)
    : path_(path), inotify_(::inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) {
    if (inotify_.get() < 0) {
        throw_errno("cannot watch", path);
    }
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << initial;
    if (::inotify_add_watch(inotify_.get(), path.c_str(), IN_CLOSE_WRITE) < 0) {
        throw_errno("cannot watch", path);
    }
    thread_ = std::make_unique<FdServiceThread>(inotify_.get(), [this] { service(); });
}

WrittenFile::~WrittenFile() {
    thread_.reset();
}

void WrittenFile::service() {
    alignas(inotify_event) char buffer[4096];
    for (;;) {
        const auto got = ::read(inotify_.get(), buffer, sizeof buffer);
        if (got < 0 && (errno == EAGAIN || errno == EINTR)) {
            return;
        }
        if (got <= 0) {
            throw_errno("cannot read the inotify events of", path_);
        }
        // Every event is a close after writing (the only one asked for): one value each.
        for (auto offset = 0L; offset < got;) {
            const auto* event = reinterpret_cast<const inotify_event*>(buffer + offset);
            offset += static_cast<long>(sizeof(inotify_event) + event->len);
            if ((event->mask & IN_CLOSE_WRITE) == 0) {
                continue;
            }
            const std::string value = read_attribute(path_);
            std::lock_guard lock(mutex_);
            writes_.push_back({std::chrono::steady_clock::now(), value});
            changed_.notify_all();
        }
    }
}

std::vector<WrittenValue> WrittenFile::writes() const {
    std::lock_guard lock(mutex_);
    return writes_;
}

bool WrittenFile::wait_for(const std::function<bool(const WrittenValue&)>& match,
                           std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] {
        for (const auto& write : writes_) {
            if (match(write)) {
                return true;
            }
        }
        return false;
    });
}

}  // namespace vibscore::hil
