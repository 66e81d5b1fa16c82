#pragma once

#include <linux/uinput.h>

#include <filesystem>
#include <string>

#include "common/unique_fd.hpp"

namespace vibscore::hil {

// What the uinput fixtures (UinputVibrator, UinputKeys) share: /dev/uinput, its ioctls, and
// finding the nodes the kernel made for a new device.

inline constexpr const char* kUinput = "/dev/uinput";

// /dev/uinput opened read-write and non-blocking; throws std::system_error naming it.
UniqueFd open_uinput();
// One ioctl on a /dev/uinput fd; throws std::system_error naming the request.
void uinput_ioctl(int fd, unsigned long request, const char* name, unsigned long argument);

// Where the kernel put a device made with UI_DEV_CREATE.
struct UinputNodes {
    std::string input_name;            // inputN, as in /sys/class/input/inputN
    std::filesystem::path event_node;  // /dev/input/eventM, existing once this is returned
};

// UI_DEV_SETUP with `setup`, UI_DEV_CREATE, and the nodes of the new device. The caller sets
// the event bits (UI_SET_EVBIT...) before. Throws when there is no event node: evdev missing.
UinputNodes create_uinput_device(int fd, const uinput_setup& setup);

}  // namespace vibscore::hil
