#include "tests/hil/uinput_device.hpp"

#include <fcntl.h>
#include <sys/ioctl.h>

#include <stdexcept>

#include "tests/hil/kernel_files.hpp"

namespace vibscore::hil {

UniqueFd open_uinput() {
    UniqueFd fd(::open(kUinput, O_RDWR | O_NONBLOCK | O_CLOEXEC));
    if (fd.get() < 0) {
        throw_errno("cannot open", kUinput);
    }
    return fd;
}

void uinput_ioctl(int fd, unsigned long request, const char* name, unsigned long argument) {
    if (::ioctl(fd, request, argument) < 0) {
        throw_errno(std::string(name) + " failed on", kUinput);
    }
}

UinputNodes create_uinput_device(int fd, const uinput_setup& setup) {
    uinput_ioctl(fd, UI_DEV_SETUP, "UI_DEV_SETUP", reinterpret_cast<unsigned long>(&setup));
    uinput_ioctl(fd, UI_DEV_CREATE, "UI_DEV_CREATE", 0);

    char sysname[64] = {};
    uinput_ioctl(fd, UI_GET_SYSNAME(sizeof sysname - 1), "UI_GET_SYSNAME",
                 reinterpret_cast<unsigned long>(sysname));
    UinputNodes nodes{sysname, {}};
    // The evdev handler names the node: /sys/devices/virtual/input/inputN/eventM.
    const auto device = std::filesystem::path("/sys/devices/virtual/input") / nodes.input_name;
    for (const auto& entry : std::filesystem::directory_iterator(device)) {
        const auto name = entry.path().filename().string();
        if (name.rfind("event", 0) == 0) {
            nodes.event_node = std::filesystem::path("/dev/input") / name;
        }
    }
    if (nodes.event_node.empty()) {
        throw std::runtime_error(device.string() + " has no eventN: is the evdev module loaded?");
    }
    // devtmpfs makes the node, not this process: wait until a client can open it.
    wait_for_path(nodes.event_node);
    return nodes;
}

}  // namespace vibscore::hil
