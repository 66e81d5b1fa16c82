#pragma once

#include <linux/input.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/unique_fd.hpp"

namespace vibscore::daemon {

// What a uinput force-feedback device is told by the kernel on behalf of its clients (fftest,
// feedbackd, a game): the other end of their EVIOCSFF, EVIOCRMFF and EV_FF writes.
class FfRequests {
  public:
    virtual ~FfRequests() = default;
    // An effect is uploaded (new, or an update of `effect.id`): 0 accepts, -errno refuses.
    virtual int upload(const ff_effect& effect) = 0;
    virtual void erase(int id) = 0;
    // EV_FF: play the effect `count` times; 0 stops it.
    virtual void play(int id, int count) = 0;
    // FF_GAIN: 0..0xffff for every effect.
    virtual void gain(int value) = 0;
};

struct UinputFfSetup {
    std::string name;
    std::string phys;
    std::vector<int> ff_bits;  // FF_RUMBLE, FF_PERIODIC, FF_SINE...
    unsigned effects_max = 16;
};

// A force-feedback input device made through /dev/uinput. Its kernel requests are read by
// service() (call it when fd() is readable), which answers each one at once: the client waits
// in its ioctl until then. Destroying it unplugs the device; its clients see ENODEV.
class UinputFfDevice {
  public:
    // Throws DeviceError naming what failed (no /dev/uinput, no permission...).
    UinputFfDevice(const UinputFfSetup& setup, FfRequests& requests);
    ~UinputFfDevice();
    UinputFfDevice(const UinputFfDevice&) = delete;
    UinputFfDevice& operator=(const UinputFfDevice&) = delete;

    int fd() const { return fd_.get(); }
    // /dev/input/eventN, as the evdev handler named it.
    const std::filesystem::path& event_node() const { return event_node_; }

    // Answers every request waiting. Throws DeviceError when the device cannot be read.
    void service();

  private:
    void answer_upload(const input_event& request);
    void answer_erase(const input_event& request);

    FfRequests& requests_;
    UniqueFd fd_;
    std::filesystem::path event_node_;
};

inline constexpr const char* kUinputPath = "/dev/uinput";

}  // namespace vibscore::daemon
