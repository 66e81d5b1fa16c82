#pragma once

#include <linux/input.h>

#include <memory>
#include <span>
#include <string>

#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

// The force-feedback features of one evdev device (its EV_FF bits and its effect memory).
struct FfFeatures {
    bool periodic = false;  // FF_PERIODIC
    bool sine = false;      // FF_SINE, a periodic waveform
    bool square = false;    // FF_SQUARE, a periodic waveform
    bool rumble = false;    // FF_RUMBLE
    bool gain = false;      // FF_GAIN
    int effect_slots = 0;   // EVIOCGEFFECTS: how many effects the device holds at once
};

// A kernel call on a force-feedback device failed. The message names the device and the errno
// text, e.g. "evdev /dev/input/event5: No such device (write)".
class FfDeviceError : public DeviceError {
  public:
    FfDeviceError(const std::string& path, const std::string& call, int error_number);

    int error_number() const noexcept { return error_number_; }

    // The device has gone (unplugged, driver unbound): ENODEV, ENOENT or EIO. The descriptor is
    // useless from then on; the device may come back under the same or another node.
    bool device_gone() const noexcept;

  private:
    int error_number_;
};

// Exactly the kernel calls the evdev backend makes on one open event device: the seam between
// the backend and the kernel, replaced by a recording fake in the unit tests. Every failure
// throws FfDeviceError.
class FfDevice {
  public:
    virtual ~FfDevice() = default;

    virtual const std::string& path() const = 0;
    virtual const std::string& name() const = 0;
    virtual FfFeatures features() const = 0;

    // EVIOCSFF. effect.id = -1 allocates a slot and stores its id in effect.id; an existing id
    // replaces that effect's parameters in place (same type and waveform only).
    virtual void upload(ff_effect& effect) = 0;

    // EVIOCRMFF: stops the effect if it plays and frees its slot.
    virtual void erase(int id) = 0;

    // Writes all events in one write() call, so the kernel handles them back to back: the
    // stop of one effect and the start of the next cannot be told apart in time.
    virtual void write(std::span<const input_event> events) = 0;
};

// Opens the event device at `path` read-write (the FF ioctls and writes need write access) and
// reads its force-feedback features (all false for a device without EV_FF). Throws FfDeviceError
// naming the path when the open or an ioctl fails, e.g. for a node that is not an event device.
std::unique_ptr<FfDevice> open_ff_device(const std::string& path);

}  // namespace vibscore::drivers
