#pragma once

#include <linux/input.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "client/editor/button_map.hpp"
#include "client/editor/buttons.hpp"
#include "common/evdev_node.hpp"

namespace vibscore::editor {

// The one libevdev call the button reader makes, so tests can feed it events without a device.
class InputEvents {
  public:
    virtual ~InputEvents() = default;
    // As libevdev_next_event(): LIBEVDEV_READ_STATUS_SUCCESS or LIBEVDEV_READ_STATUS_SYNC with
    // `event` filled in, -EAGAIN when nothing is waiting, another -errno when the device failed.
    virtual int next_event(unsigned flags, input_event& event) = 0;
};

// An evdev device (gpio-keys, a phone's keys, a keyboard) opened read-only and non-blocking,
// stamping its events with the monotonic clock. Throws DeviceError naming the path.
class EvdevDevice final : public InputEvents {
  public:
    // grab: take the keys for the editor alone, so volume keys stop changing the volume.
    EvdevDevice(std::string path, bool grab);

    int fd() const { return node_.fd(); }
    const std::string& path() const { return path_; }
    int next_event(unsigned flags, input_event& event) override;

  private:
    std::string path_;
    EvdevNode node_;
};

// A button pressed, or let go, and when (the kernel's stamp on the monotonic clock).
struct ButtonEvent {
    Button button = Button::select;
    std::chrono::microseconds at{};
    bool released = false;
    bool operator==(const ButtonEvent&) const = default;
};

// Turns key events into button presses through a ButtonMap. A key with only a short-press
// button presses it at once (and again on auto-repeat, for the four arrows). A key that also
// has a long-press button gives its short button when released before hold_ms and its long
// button once held that long: at an auto-repeat, at release, or from expire().
class ButtonReader {
  public:
    ButtonReader(InputEvents& events, ButtonMap map, std::string device);

    // Every press waiting on the device, in order. Throws DeviceError when the
    // device fails (unplugged, read error).
    std::vector<Button> read();
    // The same with their times, and (while tapping) the Select key's releases.
    std::vector<ButtonEvent> read_events();
    // While a rhythm is tapped, the key that gives Select reports its presses and releases as
    // they happen (held is a note), never as a long press.
    void set_tapping(bool tapping);
    // The long press of a key held since before now - hold_ms (`now` on the monotonic clock).
    std::optional<Button> expire(std::chrono::microseconds now);
    // How long from now until a held key becomes a long press; nullopt when none is held.
    std::optional<std::chrono::microseconds> until_long(std::chrono::microseconds now) const;

  private:
    void on_key(const input_event& event, std::vector<ButtonEvent>& presses);

    struct Held {
        unsigned code;
        std::chrono::microseconds since;
        bool fired;
    };
    InputEvents& events_;
    ButtonMap map_;
    std::string device_;
    std::optional<Held> held_;
    bool tapping_ = false;
};

}  // namespace vibscore::editor
