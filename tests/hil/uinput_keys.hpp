#pragma once

#include <linux/input.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/unique_fd.hpp"

namespace vibscore::hil {

struct UinputKeysOptions {
    std::string name = "vibscore-hil-keys";
    input_id id{BUS_VIRTUAL, 0x1209, 0x0002, 1};
    std::vector<unsigned> keys;  // KEY_... codes the device has
    // EV_REP: the input core repeats a held key itself (value 2, after 250 ms, every 33 ms),
    // as for gpio-keys with `autorepeat` in the device tree.
    bool auto_repeat = false;

    // Looks like a phone's keys: gpio-keys on the host bus with volume up, volume down, power.
    static UinputKeysOptions phone_keys(bool auto_repeat);
};

// A key device (EV_KEY) made with /dev/uinput, standing in for gpio-keys or a keyboard. A test
// presses its keys; a client reads them through event_node(), the real evdev interface. Events
// reach every open evdev fd before press() and release() return, so a client can poll for them.
class UinputKeys {
  public:
    explicit UinputKeys(UinputKeysOptions options);
    // Closing /dev/uinput removes a device still there.
    ~UinputKeys() = default;
    UinputKeys(const UinputKeys&) = delete;
    UinputKeys& operator=(const UinputKeys&) = delete;

    // /dev/input/eventN while the device exists.
    const std::filesystem::path& event_node() const { return event_node_; }
    bool exists() const { return uinput_.get() >= 0; }

    // Key down (held until release()), then SYN_REPORT.
    void press(unsigned code);
    // Key up, then SYN_REPORT.
    void release(unsigned code);
    // press() and release() at once: a short press.
    void tap(unsigned code);

    // Removes the device (UI_DEV_DESTROY), as if unplugged: clients' reads fail with ENODEV.
    void destroy();

  private:
    void write_event(unsigned type, unsigned code, int value);

    UniqueFd uinput_;
    std::filesystem::path event_node_;
};

}  // namespace vibscore::hil
