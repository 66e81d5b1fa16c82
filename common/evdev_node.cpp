#include "common/evdev_node.hpp"

#include <fcntl.h>
#include <libevdev/libevdev.h>

#include <cerrno>
#include <cstring>

namespace vibscore {

namespace {

std::string describe(const std::string& path, EvdevOpenError::Step step, int error_number) {
    const char* what =
        step == EvdevOpenError::Step::open ? ": cannot open: " : ": not an evdev device: ";
    return path + what + std::strerror(error_number);
}

}  // namespace

EvdevOpenError::EvdevOpenError(const std::string& path, Step step, int error_number)
    : DeviceError(describe(path, step, error_number)), step_(step), error_number_(error_number) {}

void EvdevNode::Free::operator()(libevdev* device) const noexcept {
    libevdev_free(device);
}

EvdevNode::EvdevNode(const std::string& path, int flags)
    : fd_(::open(path.c_str(), flags | O_CLOEXEC)) {
    if (fd_.get() < 0) {
        throw EvdevOpenError(path, EvdevOpenError::Step::open, errno);
    }
    libevdev* device = nullptr;
    if (const int created = libevdev_new_from_fd(fd_.get(), &device); created < 0) {
        throw EvdevOpenError(path, EvdevOpenError::Step::read, -created);
    }
    device_.reset(device);
}

}  // namespace vibscore
