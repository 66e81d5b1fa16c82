#include "feedback/user_scores_watch.hpp"

#include <sys/inotify.h>

#include <cerrno>
#include <system_error>

namespace vibscore::feedback {

FileWatch::FileWatch(daemon::EventLoop& loop, std::filesystem::path file,
                     std::function<void()> changed)
    : name_(file.filename().string()), changed_(std::move(changed)) {
    const auto directory = file.parent_path();
    sd_event_source* source = nullptr;
    const int result =
        sd_event_add_inotify(loop.get(), &source, directory.c_str(),
                             IN_CLOSE_WRITE | IN_MOVED_TO | IN_MOVED_FROM | IN_DELETE | IN_ONLYDIR,
                             &FileWatch::on_event, this);
    if (result < 0) {
        throw std::system_error(-result, std::generic_category(),
                                "cannot watch " + directory.string());
    }
    source_.reset(source);
}

int FileWatch::on_event(sd_event_source*, const struct inotify_event* event, void* self) {
    auto* watch = static_cast<FileWatch*>(self);
    if (event->len > 0 && watch->name_ == event->name) {
        watch->changed_();
    }
    return 0;
}

}  // namespace vibscore::feedback
