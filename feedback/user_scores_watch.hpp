#pragma once

#include <systemd/sd-event.h>

#include <filesystem>
#include <functional>
#include <string>

#include "common/event_loop.hpp"

namespace vibscore::feedback {

// Calls `changed` from `loop` when a file may have changed: written in place, replaced by a
// rename (as an atomic write and most editors do), or removed. It watches the file's directory,
// which must exist, so that a file made later is seen too. Throws std::system_error when the
// directory cannot be watched.
class FileWatch {
  public:
    FileWatch(daemon::EventLoop& loop, std::filesystem::path file, std::function<void()> changed);
    FileWatch(const FileWatch&) = delete;
    FileWatch& operator=(const FileWatch&) = delete;

  private:
    static int on_event(sd_event_source* source, const struct inotify_event* event, void* self);

    std::string name_;
    std::function<void()> changed_;
    daemon::EventSourcePtr source_;
};

}  // namespace vibscore::feedback
