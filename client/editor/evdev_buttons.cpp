#include "client/editor/evdev_buttons.hpp"

#include <fcntl.h>
#include <libevdev/libevdev.h>

#include <cstring>
#include <ctime>

namespace vibscore::editor {

EvdevDevice::EvdevDevice(std::string path, bool grab)
    : path_(std::move(path)), node_(path_, O_RDONLY | O_NONBLOCK) {
    libevdev* const device = node_.device();
    if (!libevdev_has_event_type(device, EV_KEY)) {
        throw DeviceError(path_ + " (" + libevdev_get_name(device) + ") has no keys");
    }
    // Hold times are measured against CLOCK_MONOTONIC, as expire() is called with.
    if (const int set = libevdev_set_clock_id(device, CLOCK_MONOTONIC); set < 0) {
        throw DeviceError(path_ + ": cannot use the monotonic clock: " + std::strerror(-set));
    }
    if (grab) {
        if (const int grabbed = libevdev_grab(device, LIBEVDEV_GRAB); grabbed < 0) {
            throw DeviceError(path_ + ": cannot grab: " + std::strerror(-grabbed));
        }
    }
}

int EvdevDevice::next_event(unsigned flags, input_event& event) {
    return libevdev_next_event(node_.device(), flags, &event);
}

namespace {

std::chrono::microseconds stamp(const input_event& event) {
    return std::chrono::seconds(event.input_event_sec) +
           std::chrono::microseconds(event.input_event_usec);
}

bool repeats(Button button) {
    return button == Button::up || button == Button::down || button == Button::left ||
           button == Button::right;
}

}  // namespace

ButtonReader::ButtonReader(InputEvents& events, ButtonMap map, std::string device)
    : events_(events), map_(std::move(map)), device_(std::move(device)) {}

void ButtonReader::set_tapping(bool tapping) {
    tapping_ = tapping;
    held_.reset();
}

std::vector<Button> ButtonReader::read() {
    std::vector<Button> presses;
    for (const auto& event : read_events()) {
        if (!event.released) {
            presses.push_back(event.button);
        }
    }
    return presses;
}

std::vector<ButtonEvent> ButtonReader::read_events() {
    std::vector<ButtonEvent> presses;
    input_event event{};
    while (true) {
        const int status = events_.next_event(LIBEVDEV_READ_FLAG_NORMAL, event);
        if (status == -EAGAIN) {
            return presses;
        }
        if (status == LIBEVDEV_READ_STATUS_SYNC) {
            // Events were dropped: catch up with the device's state and forget a held key,
            // whose release may be among what was lost.
            int sync = status;
            while (sync == LIBEVDEV_READ_STATUS_SYNC) {
                sync = events_.next_event(LIBEVDEV_READ_FLAG_SYNC, event);
            }
            if (sync < 0 && sync != -EAGAIN) {
                throw DeviceError(device_ + ": read failed: " + std::strerror(-sync));
            }
            held_.reset();
            continue;
        }
        if (status < 0) {
            throw DeviceError(device_ + ": read failed: " + std::strerror(-status));
        }
        if (event.type == EV_KEY) {
            on_key(event, presses);
        }
    }
}

void ButtonReader::on_key(const input_event& event, std::vector<ButtonEvent>& presses) {
    const unsigned code = event.code;
    const auto now = stamp(event);
    const auto hold = std::chrono::milliseconds(map_.hold_ms());
    const auto short_button = map_.short_press(code);
    if (tapping_ && short_button == Button::select) {
        // Held is a note: the press and the release as they come, no long press.
        if (event.value == 1 || event.value == 0) {
            presses.push_back({Button::select, now, event.value == 0});
        }
        return;
    }
    if (!map_.has_long_press(code)) {
        const bool press =
            event.value == 1 || (event.value == 2 && short_button && repeats(*short_button));
        if (press && short_button) {
            presses.push_back({*short_button, now});
        }
        return;
    }
    switch (event.value) {
        case 1:
            if (held_ && !held_->fired) {
                // Another key came first: the earlier one was a short press.
                if (const auto earlier = map_.short_press(held_->code)) {
                    presses.push_back({*earlier, now});
                }
            }
            held_ = Held{code, now, false};
            return;
        case 2:
            if (held_ && held_->code == code && !held_->fired && now - held_->since >= hold) {
                held_->fired = true;
                presses.push_back({*map_.long_press(code), now});
            }
            return;
        case 0:
            if (held_ && held_->code == code) {
                if (!held_->fired) {
                    if (now - held_->since >= hold) {
                        presses.push_back({*map_.long_press(code), now});
                    } else if (short_button) {
                        presses.push_back({*short_button, held_->since});
                    }
                }
                held_.reset();
            }
            return;
        default:
            return;
    }
}

std::optional<Button> ButtonReader::expire(std::chrono::microseconds now) {
    if (!held_ || held_->fired || now - held_->since < std::chrono::milliseconds(map_.hold_ms())) {
        return std::nullopt;
    }
    held_->fired = true;
    return map_.long_press(held_->code);
}

std::optional<std::chrono::microseconds> ButtonReader::until_long(
    std::chrono::microseconds now) const {
    if (!held_ || held_->fired) {
        return std::nullopt;
    }
    const auto left = held_->since + std::chrono::milliseconds(map_.hold_ms()) - now;
    return left < std::chrono::microseconds(0) ? std::chrono::microseconds(0) : left;
}

}  // namespace vibscore::editor
