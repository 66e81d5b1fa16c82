#include "daemon/drivers/ff_device.hpp"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "common/evdev_node.hpp"

namespace vibscore::drivers {

FfDeviceError::FfDeviceError(const std::string& path, const std::string& call, int error_number)
    : DeviceError("evdev " + path + ": " + std::strerror(error_number) + " (" + call + ")"),
      error_number_(error_number) {}

bool FfDeviceError::device_gone() const noexcept {
    return error_number_ == ENODEV || error_number_ == ENOENT || error_number_ == EIO;
}

namespace {

// Read-write: the FF ioctls and writes need write access.
EvdevNode open_node(const std::string& path) {
    try {
        return EvdevNode(path, O_RDWR | O_NONBLOCK);
    } catch (const EvdevOpenError& error) {
        const bool opening = error.step() == EvdevOpenError::Step::open;
        throw FfDeviceError(path, opening ? "open" : "reading the device's capabilities",
                            error.error_number());
    }
}

class KernelFfDevice : public FfDevice {
  public:
    explicit KernelFfDevice(std::string path) : path_(std::move(path)), node_(open_node(path_)) {
        libevdev* const evdev = node_.device();
        name_ = libevdev_get_name(evdev);
        const auto has = [&](unsigned code) {
            return libevdev_has_event_code(evdev, EV_FF, code) != 0;
        };
        features_.periodic = has(FF_PERIODIC);
        features_.sine = has(FF_SINE);
        features_.square = has(FF_SQUARE);
        features_.rumble = has(FF_RUMBLE);
        features_.gain = has(FF_GAIN);
        int slots = 0;
        if (libevdev_has_event_type(evdev, EV_FF) && retry_ioctl(EVIOCGEFFECTS, &slots) < 0) {
            throw FfDeviceError(path_, "EVIOCGEFFECTS", errno);
        }
        features_.effect_slots = slots;
    }

    const std::string& path() const override { return path_; }
    const std::string& name() const override { return name_; }
    FfFeatures features() const override { return features_; }

    void upload(ff_effect& effect) override {
        if (retry_ioctl(EVIOCSFF, &effect) < 0) {
            throw FfDeviceError(path_, "EVIOCSFF", errno);
        }
    }

    void erase(int id) override {
        // EVIOCRMFF takes the id itself as the argument, not a pointer to it.
        if (retry_ioctl(EVIOCRMFF, static_cast<long>(id)) < 0) {
            throw FfDeviceError(path_, "EVIOCRMFF", errno);
        }
    }

    void write(std::span<const input_event> events) override {
        ssize_t written;
        do {
            written = ::write(node_.fd(), events.data(), events.size_bytes());
        } while (written < 0 && errno == EINTR);
        if (written < 0) {
            throw FfDeviceError(path_, "write", errno);
        }
        if (static_cast<std::size_t>(written) != events.size_bytes()) {
            // evdev stops at the first event it cannot take and reports what went through.
            throw DeviceError("evdev " + path_ + ": wrote " + std::to_string(written) + " of " +
                              std::to_string(events.size_bytes()) + " bytes of FF events");
        }
    }

  private:
    // An interrupted ioctl has done nothing (the evdev mutex wait is what gets interrupted).
    template <typename Arg>
    int retry_ioctl(unsigned long request, Arg arg) {
        int result;
        do {
            result = ::ioctl(node_.fd(), request, arg);
        } while (result < 0 && errno == EINTR);
        return result;
    }

    std::string path_;
    EvdevNode node_;
    std::string name_;
    FfFeatures features_;
};

}  // namespace

std::unique_ptr<FfDevice> open_ff_device(const std::string& path) {
    return std::make_unique<KernelFfDevice>(path);
}

}  // namespace vibscore::drivers
