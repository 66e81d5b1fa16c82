#include "daemon/virtual_vibra/uinput_ff_device.hpp"

#include <fcntl.h>
#include <linux/uinput.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/device_error.hpp"

namespace vibscore::daemon {

namespace {

void control(int fd, unsigned long request, const char* name, unsigned long argument) {
    if (::ioctl(fd, request, argument) < 0) {
        throw DeviceError(std::string(kUinputPath) + ": " + name + ": " + std::strerror(errno));
    }
}

// /dev/input/eventN of the device uinput made, from its sysfs directory.
std::filesystem::path event_node_of(int fd) {
    char sysname[64] = {};
    control(fd, UI_GET_SYSNAME(sizeof sysname - 1), "UI_GET_SYSNAME",
            reinterpret_cast<unsigned long>(sysname));
    const auto device = std::filesystem::path("/sys/devices/virtual/input") / sysname;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(device, error)) {
        const auto name = entry.path().filename().string();
        if (name.starts_with("event")) {
            return std::filesystem::path("/dev/input") / name;
        }
    }
    // No evdev handler (module not loaded): clients cannot reach the device.
    throw DeviceError(device.string() + " has no event node: is the evdev module loaded?");
}

}  // namespace

UinputFfDevice::UinputFfDevice(const UinputFfSetup& setup, FfRequests& requests)
    : requests_(requests), fd_(::open(kUinputPath, O_RDWR | O_NONBLOCK | O_CLOEXEC)) {
    if (fd_.get() < 0) {
        throw DeviceError(std::string("cannot open ") + kUinputPath + ": " + std::strerror(errno));
    }
    control(fd_.get(), UI_SET_EVBIT, "UI_SET_EVBIT EV_FF", EV_FF);
    for (const int bit : setup.ff_bits) {
        control(fd_.get(), UI_SET_FFBIT, "UI_SET_FFBIT", static_cast<unsigned long>(bit));
    }
    control(fd_.get(), UI_SET_PHYS, "UI_SET_PHYS",
            reinterpret_cast<unsigned long>(setup.phys.c_str()));
    uinput_setup device{};
    device.id.bustype = BUS_VIRTUAL;
    std::strncpy(device.name, setup.name.c_str(), UINPUT_MAX_NAME_SIZE - 1);
    device.ff_effects_max = setup.effects_max;
    control(fd_.get(), UI_DEV_SETUP, "UI_DEV_SETUP", reinterpret_cast<unsigned long>(&device));
    control(fd_.get(), UI_DEV_CREATE, "UI_DEV_CREATE", 0);
    try {
        event_node_ = event_node_of(fd_.get());
    } catch (...) {
        ::ioctl(fd_.get(), UI_DEV_DESTROY);
        throw;
    }
}

UinputFfDevice::~UinputFfDevice() {
    // Requests still waiting are failed with ENODEV by the kernel itself.
    ::ioctl(fd_.get(), UI_DEV_DESTROY);
}

void UinputFfDevice::service() {
    input_event event{};
    for (;;) {
        const auto got = ::read(fd_.get(), &event, sizeof event);
        if (got < 0 && (errno == EAGAIN || errno == EINTR)) {
            return;
        }
        if (got != static_cast<ssize_t>(sizeof event)) {
            throw DeviceError(std::string(kUinputPath) + ": cannot read a request: " +
                              (got < 0 ? std::strerror(errno) : "short read"));
        }
        if (event.type == EV_UINPUT && event.code == UI_FF_UPLOAD) {
            answer_upload(event);
        } else if (event.type == EV_UINPUT && event.code == UI_FF_ERASE) {
            answer_erase(event);
        } else if (event.type == EV_FF && event.code == FF_GAIN) {
            requests_.gain(event.value);
        } else if (event.type == EV_FF && event.code < FF_GAIN) {
            requests_.play(event.code, event.value);  // the code is the effect's id
        }
    }
}

void UinputFfDevice::answer_upload(const input_event& request) {
    uinput_ff_upload upload{};
    upload.request_id = static_cast<__u32>(request.value);
    control(fd_.get(), UI_BEGIN_FF_UPLOAD, "UI_BEGIN_FF_UPLOAD",
            reinterpret_cast<unsigned long>(&upload));
    try {
        upload.retval = requests_.upload(upload.effect);
    } catch (const std::exception&) {
        upload.retval = -EINVAL;  // the client must have an answer, or it waits 30 s in its ioctl
    }
    control(fd_.get(), UI_END_FF_UPLOAD, "UI_END_FF_UPLOAD",
            reinterpret_cast<unsigned long>(&upload));
}

void UinputFfDevice::answer_erase(const input_event& request) {
    uinput_ff_erase erase{};
    erase.request_id = static_cast<__u32>(request.value);
    control(fd_.get(), UI_BEGIN_FF_ERASE, "UI_BEGIN_FF_ERASE",
            reinterpret_cast<unsigned long>(&erase));
    try {
        requests_.erase(static_cast<int>(erase.effect_id));
    } catch (const std::exception&) {
        // Erased all the same: the kernel forgets the effect whatever the answer.
    }
    erase.retval = 0;
    control(fd_.get(), UI_END_FF_ERASE, "UI_END_FF_ERASE", reinterpret_cast<unsigned long>(&erase));
}

}  // namespace vibscore::daemon
