#include "tests/hil/uinput_keys.hpp"

#include <linux/uinput.h>
#include <unistd.h>

#include <cstring>

#include "tests/hil/kernel_files.hpp"
#include "tests/hil/uinput_device.hpp"

namespace vibscore::hil {

UinputKeysOptions UinputKeysOptions::phone_keys(bool auto_repeat) {
    UinputKeysOptions options;
    options.name = "gpio-keys";
    options.id = {BUS_HOST, 0x0001, 0x0001, 0x0100};
    options.keys = {KEY_VOLUMEUP, KEY_VOLUMEDOWN, KEY_POWER};
    options.auto_repeat = auto_repeat;
    return options;
}

UinputKeys::UinputKeys(UinputKeysOptions options) {
    UniqueFd fd = open_uinput();
    uinput_ioctl(fd.get(), UI_SET_EVBIT, "UI_SET_EVBIT EV_KEY", EV_KEY);
    for (const unsigned code : options.keys) {
        uinput_ioctl(fd.get(), UI_SET_KEYBIT, "UI_SET_KEYBIT", code);
    }
    if (options.auto_repeat) {
        uinput_ioctl(fd.get(), UI_SET_EVBIT, "UI_SET_EVBIT EV_REP", EV_REP);
    }
    uinput_setup setup{};
    setup.id = options.id;
    std::strncpy(setup.name, options.name.c_str(), UINPUT_MAX_NAME_SIZE - 1);
    event_node_ = create_uinput_device(fd.get(), setup).event_node;
    uinput_ = std::move(fd);
}

void UinputKeys::press(unsigned code) {
    write_event(EV_KEY, code, 1);
    write_event(EV_SYN, SYN_REPORT, 0);
}

void UinputKeys::release(unsigned code) {
    write_event(EV_KEY, code, 0);
    write_event(EV_SYN, SYN_REPORT, 0);
}

void UinputKeys::tap(unsigned code) {
    press(code);
    release(code);
}

void UinputKeys::destroy() {
    uinput_ioctl(uinput_.get(), UI_DEV_DESTROY, "UI_DEV_DESTROY", 0);
    uinput_.close();
}

void UinputKeys::write_event(unsigned type, unsigned code, int value) {
    // A zero time: the kernel stamps the event when it passes it on, with the clients' clock.
    input_event event{};
    event.type = static_cast<__u16>(type);
    event.code = static_cast<__u16>(code);
    event.value = value;
    if (::write(uinput_.get(), &event, sizeof event) != static_cast<ssize_t>(sizeof event)) {
        throw_errno("cannot write an event to", kUinput);
    }
}

}  // namespace vibscore::hil
