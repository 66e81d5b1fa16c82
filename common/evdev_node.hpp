#pragma once

#include <memory>
#include <string>

#include "common/device_error.hpp"
#include "common/unique_fd.hpp"

struct libevdev;

namespace vibscore {

// Opening an event device failed: open() itself (no such node, no permission), or libevdev
// reading it (not an event device). Each user tells the two apart in its own terms.
class EvdevOpenError : public DeviceError {
  public:
    enum class Step { open, read };

    // The message names the path, the step and the errno text, e.g.
    // "/dev/null: not an evdev device: Inappropriate ioctl for device".
    EvdevOpenError(const std::string& path, Step step, int error_number);

    Step step() const noexcept { return step_; }
    int error_number() const noexcept { return error_number_; }

  private:
    Step step_;
    int error_number_;
};

// An event device node (/dev/input/eventN) open, with libevdev's handle on it: its name, its
// event bits, its events. The evdev actuator, its discovery and the editor's buttons all hold
// one.
class EvdevNode {
  public:
    // Opens `path` with `flags` (O_RDONLY or O_RDWR, O_NONBLOCK...; O_CLOEXEC is added) and has
    // libevdev read the device. Throws EvdevOpenError.
    EvdevNode(const std::string& path, int flags);

    int fd() const noexcept { return fd_.get(); }
    libevdev* device() const noexcept { return device_.get(); }

  private:
    struct Free {
        void operator()(libevdev* device) const noexcept;
    };
    UniqueFd fd_;  // declared first: closed after libevdev lets go of it (and of a grab)
    std::unique_ptr<libevdev, Free> device_;
};

}  // namespace vibscore
