// The editor's buttons from real keys: EvdevDevice and ButtonReader (client/editor) reading a
// UinputKeys device through /dev/input/eventN, with the phone map parsed as `--keymap` is.
// tests/unit/editor_evdev_test.cpp covers the reader over a fake of libevdev; this is what the
// kernel really does: its timestamps, its auto-repeat, EVIOCGRAB and an unplugged device.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "client/editor/button_map.hpp"
#include "client/editor/evdev_buttons.hpp"
#include "common/unique_fd.hpp"
#include "daemon/drivers/actuator.hpp"
#include "tests/hil/uinput_keys.hpp"

namespace vibscore::hil {
namespace {

using editor::Button;
using editor::ButtonMap;
using editor::ButtonReader;
using editor::EvdevDevice;
using std::chrono::duration_cast;
using std::chrono::microseconds;
using std::chrono::milliseconds;
using std::chrono::steady_clock;
using namespace std::chrono_literals;

// The phone map of docs/editor.md spelled out as a --keymap, so the real parser builds it.
constexpr const char* kPhoneKeymap =
    "none,up=KEY_VOLUMEUP,right=long:KEY_VOLUMEUP,down=KEY_VOLUMEDOWN,left=long:KEY_VOLUMEDOWN,"
    "select=KEY_POWER,back=long:KEY_POWER,hold-ms=500";

using Names = std::vector<std::string_view>;

Names names(const std::vector<Button>& buttons) {
    Names result;
    for (const Button button : buttons) {
        result.push_back(editor::to_string(button));
    }
    return result;
}

std::string_view name(std::optional<Button> button) {
    return button ? editor::to_string(*button) : "nothing";
}

// steady_clock is CLOCK_MONOTONIC, the clock EvdevDevice has the kernel stamp events with.
microseconds monotonic_now() {
    return duration_cast<microseconds>(steady_clock::now().time_since_epoch());
}

// Waits up to `timeout` for `fd` to have events (or to fail); false when none came.
bool readable(int fd, milliseconds timeout) {
    pollfd wait{fd, POLLIN, 0};
    const int ready = ::poll(&wait, 1, static_cast<int>(timeout.count()));
    EXPECT_GE(ready, 0) << std::strerror(errno);
    return ready > 0;
}

void append(std::vector<Button>& presses, const std::vector<Button>& more) {
    presses.insert(presses.end(), more.begin(), more.end());
}

// As the editor reads: wait on the device's fd, then read everything waiting. Stops once
// `count` presses came or after `timeout`.
std::vector<Button> read_presses(ButtonReader& reader, int fd, std::size_t count,
                                 milliseconds timeout = 2s) {
    std::vector<Button> presses;
    const auto deadline = steady_clock::now() + timeout;
    while (presses.size() < count) {
        const auto left = duration_cast<milliseconds>(deadline - steady_clock::now());
        if (left <= 0ms || !readable(fd, left)) {
            break;
        }
        append(presses, reader.read());
    }
    return presses;
}

// Key events as (code, value).
using KeyEvents = std::vector<std::pair<int, int>>;

// The key events waiting on a plain, non-blocking evdev fd.
KeyEvents key_events(int fd) {
    KeyEvents keys;
    input_event event{};
    while (::read(fd, &event, sizeof event) == static_cast<ssize_t>(sizeof event)) {
        if (event.type == EV_KEY) {
            keys.emplace_back(event.code, event.value);
        }
    }
    EXPECT_EQ(errno, EAGAIN) << std::strerror(errno);
    return keys;
}

// Passes the device's events on to the reader and counts the kernel's auto-repeats (value 2),
// so a test can wait until a key has been held through more of them.
class RepeatCounter final : public editor::InputEvents {
  public:
    explicit RepeatCounter(editor::InputEvents& events) : events_(events) {}
    int next_event(unsigned flags, input_event& event) override {
        const int status = events_.next_event(flags, event);
        if (status == LIBEVDEV_READ_STATUS_SUCCESS && event.type == EV_KEY && event.value == 2) {
            ++repeats_;
        }
        return status;
    }
    int repeats() const { return repeats_; }

  private:
    editor::InputEvents& events_;
    int repeats_ = 0;
};

TEST(EditorButtonsSmoke, ShortPressesOfThePhoneKeysGiveTheirShortButtonsInOrder) {
    UinputKeys keys(UinputKeysOptions::phone_keys(false));
    const std::string node = keys.event_node().string();
    EvdevDevice device(node, false);
    ButtonReader reader(device, ButtonMap::parse(kPhoneKeymap), node);
    keys.tap(KEY_VOLUMEUP);
    keys.tap(KEY_VOLUMEDOWN);
    keys.tap(KEY_POWER);
    keys.tap(KEY_VOLUMEDOWN);
    EXPECT_EQ(names(read_presses(reader, device.fd(), 4)), (Names{"up", "down", "select", "down"}));
    EXPECT_FALSE(readable(device.fd(), 100ms));
    EXPECT_TRUE(reader.read().empty());
}

TEST(EditorButtonsSmoke, AKeyHeldWithKernelAutoRepeatGivesItsLongButtonOnce) {
    UinputKeys keys(UinputKeysOptions::phone_keys(true));
    const std::string node = keys.event_node().string();
    EvdevDevice device(node, false);
    RepeatCounter events(device);
    const ButtonMap map = ButtonMap::parse(kPhoneKeymap);
    ButtonReader reader(events, map, node);

    const auto pressed = steady_clock::now();
    keys.press(KEY_VOLUMEDOWN);
    // No expire() here: the kernel's repeats alone turn the hold into a long press.
    const auto presses = read_presses(reader, device.fd(), 1, 3s);
    ASSERT_EQ(names(presses), Names{"left"});
    EXPECT_GE(steady_clock::now() - pressed, milliseconds(map.hold_ms()));
    EXPECT_GE(events.repeats(), 1);

    // Held on through more repeats, the key gives nothing more: not from them, not from
    // expire(), not when released.
    const int repeats_at_long = events.repeats();
    std::vector<Button> later;
    while (events.repeats() < repeats_at_long + 5 && readable(device.fd(), 1s)) {
        append(later, reader.read());
    }
    EXPECT_GE(events.repeats(), repeats_at_long + 5);
    EXPECT_EQ(name(reader.expire(monotonic_now())), "nothing");
    keys.release(KEY_VOLUMEDOWN);
    ASSERT_TRUE(readable(device.fd(), 1s));
    append(later, reader.read());
    EXPECT_EQ(names(later), Names{});
}

TEST(EditorButtonsSmoke, WithoutAutoRepeatAHeldKeyGivesItsLongButtonOnceFromExpire) {
    UinputKeys keys(UinputKeysOptions::phone_keys(false));
    const std::string node = keys.event_node().string();
    EvdevDevice device(node, false);
    const ButtonMap map = ButtonMap::parse(kPhoneKeymap);
    ButtonReader reader(device, map, node);

    keys.press(KEY_POWER);
    ASSERT_TRUE(readable(device.fd(), 1s));
    EXPECT_EQ(names(reader.read()), Names{});  // short or long is not known yet
    EXPECT_EQ(name(reader.expire(monotonic_now())), "nothing");
    const auto left = reader.until_long(monotonic_now());
    ASSERT_TRUE(left.has_value());
    EXPECT_LE(*left, milliseconds(map.hold_ms()));

    // The editor's wait (editor_app.cpp): poll the device until the hold is long. Nothing
    // arrives meanwhile: the device does not repeat.
    EXPECT_FALSE(readable(device.fd(), duration_cast<milliseconds>(*left) + 1ms));
    EXPECT_EQ(name(reader.expire(monotonic_now())), "back");
    EXPECT_EQ(name(reader.expire(monotonic_now())), "nothing");
    EXPECT_FALSE(reader.until_long(monotonic_now()).has_value());

    keys.release(KEY_POWER);
    ASSERT_TRUE(readable(device.fd(), 1s));
    EXPECT_EQ(names(reader.read()), Names{});  // its long press was given already
}

TEST(EditorButtonsSmoke, WhileTheEditorGrabsTheKeysAnotherReaderSeesNone) {
    UinputKeys keys(UinputKeysOptions::phone_keys(false));
    const std::string node = keys.event_node().string();
    const UniqueFd other(::open(node.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
    ASSERT_GE(other.get(), 0) << node << ": " << std::strerror(errno);
    {
        EvdevDevice device(node, true);
        ButtonReader reader(device, ButtonMap::parse(kPhoneKeymap), node);
        keys.tap(KEY_POWER);
        EXPECT_EQ(names(read_presses(reader, device.fd(), 1)), Names{"select"});
        // The kernel hands an event to every client before uinput's write() returns: had this
        // one been given the press, it would be waiting there now.
        EXPECT_FALSE(readable(other.get(), 100ms)) << "the other reader was given the press";
        EXPECT_EQ(key_events(other.get()), KeyEvents{});
    }
    // Closing the grabbing fd lets go: the other reader gets the keys again, so its silence
    // above was the grab's doing.
    keys.tap(KEY_POWER);
    ASSERT_TRUE(readable(other.get(), 1s));
    EXPECT_EQ(key_events(other.get()), (KeyEvents{{KEY_POWER, 1}, {KEY_POWER, 0}}));
}

TEST(EditorButtonsSmoke, UnpluggingTheKeysMakesReadThrowNamingThePath) {
    UinputKeys keys(UinputKeysOptions::phone_keys(false));
    const std::string node = keys.event_node().string();
    EvdevDevice device(node, false);
    ButtonReader reader(device, ButtonMap::parse(kPhoneKeymap), node);
    keys.tap(KEY_VOLUMEUP);
    ASSERT_EQ(names(read_presses(reader, device.fd(), 1)), Names{"up"});

    keys.destroy();
    // The hangup wakes a poll at once, as it wakes the editor's.
    ASSERT_TRUE(readable(device.fd(), 1s));
    try {
        const auto presses = reader.read();
        ADD_FAILURE() << "read() after the unplug gave " << presses.size() << " presses";
    } catch (const drivers::DeviceError& error) {
        EXPECT_NE(std::string(error.what()).find(node), std::string::npos) << error.what();
    }
    // The node went with the device: opening it again fails too, naming it.
    try {
        EvdevDevice again(node, false);
        ADD_FAILURE() << node << " opened after the unplug";
    } catch (const drivers::DeviceError& error) {
        EXPECT_NE(std::string(error.what()).find(node), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace vibscore::hil
