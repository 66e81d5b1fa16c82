// Buttons from an evdev device: the key map, and the reader over a fake of libevdev's
// next_event (the one call it makes).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <libevdev/libevdev.h>

#include <deque>
#include <stdexcept>

#include "client/editor/button_map.hpp"
#include "client/editor/evdev_buttons.hpp"
#include "daemon/drivers/actuator.hpp"

namespace vibscore {
namespace {

using editor::Button;
using editor::ButtonMap;
using editor::ButtonReader;
using std::chrono::microseconds;
using std::chrono::milliseconds;

// What libevdev_next_event would return, one call at a time; -EAGAIN when the queue is empty.
class FakeEvents : public editor::InputEvents {
  public:
    struct Reply {
        int status;
        input_event event;
        unsigned expected_flags;
    };
    void key(unsigned code, int value, int ms) {
        replies.push_back({LIBEVDEV_READ_STATUS_SUCCESS, event(EV_KEY, code, value, ms),
                           LIBEVDEV_READ_FLAG_NORMAL});
        replies.push_back({LIBEVDEV_READ_STATUS_SUCCESS, event(EV_SYN, SYN_REPORT, 0, ms),
                           LIBEVDEV_READ_FLAG_NORMAL});
    }
    static input_event event(unsigned type, unsigned code, int value, int ms) {
        input_event e{};
        e.input_event_sec = ms / 1000;
        e.input_event_usec = (ms % 1000) * 1000;
        e.type = static_cast<std::uint16_t>(type);
        e.code = static_cast<std::uint16_t>(code);
        e.value = value;
        return e;
    }
    int next_event(unsigned flags, input_event& event) override {
        ++calls;
        if (replies.empty()) {
            return -EAGAIN;
        }
        const Reply reply = replies.front();
        replies.pop_front();
        EXPECT_EQ(flags, reply.expected_flags);
        event = reply.event;
        return reply.status;
    }
    std::deque<Reply> replies;
    int calls = 0;
};

ButtonMap six_keys() {
    return ButtonMap::parse(
        "none,up=KEY_UP,down=KEY_DOWN,left=KEY_LEFT,right=KEY_RIGHT,select=KEY_ENTER,back=KEY_ESC");
}

TEST(ButtonMap, ThePhoneMapGivesSixButtonsFromThreeKeys) {
    const auto map = ButtonMap::phone();
    EXPECT_EQ(map.short_press(KEY_VOLUMEUP), Button::up);
    EXPECT_EQ(map.long_press(KEY_VOLUMEUP), Button::right);
    EXPECT_EQ(map.short_press(KEY_VOLUMEDOWN), Button::down);
    EXPECT_EQ(map.long_press(KEY_VOLUMEDOWN), Button::left);
    EXPECT_EQ(map.short_press(KEY_POWER), Button::select);
    EXPECT_EQ(map.long_press(KEY_POWER), Button::back);
    EXPECT_EQ(map.hold_ms(), 500);
}

TEST(ButtonMap, ParsesNamesCodesLongPressesAndTheHoldTime) {
    const auto map = ButtonMap::parse("select=KEY_ENTER, back=long:28 ,left=105,hold-ms=300");
    EXPECT_EQ(map.short_press(KEY_ENTER), Button::select);
    EXPECT_EQ(map.long_press(KEY_ENTER), Button::back);
    EXPECT_EQ(map.short_press(KEY_LEFT), Button::left);
    EXPECT_FALSE(map.long_press(KEY_VOLUMEDOWN));          // left moved off the volume key
    EXPECT_EQ(map.short_press(KEY_POWER), std::nullopt);   // select moved too
    EXPECT_EQ(map.short_press(KEY_VOLUMEUP), Button::up);  // untouched entries stay
    EXPECT_EQ(map.hold_ms(), 300);
    EXPECT_EQ(ButtonMap::key_name(KEY_VOLUMEUP), "KEY_VOLUMEUP");
}

TEST(ButtonMap, NamesTheEntryAtFault) {
    const auto message = [](const char* text) {
        try {
            ButtonMap::parse(text);
        } catch (const std::invalid_argument& error) {
            return std::string(error.what());
        }
        return std::string("<accepted>");
    };
    EXPECT_THAT(message("up=KEY_NOPE"),
                ::testing::HasSubstr("\"up=KEY_NOPE\": \"KEY_NOPE\" is not a key"));
    EXPECT_THAT(message("jump=KEY_UP"), ::testing::HasSubstr("\"jump\" is not a button"));
    EXPECT_THAT(message("up"), ::testing::HasSubstr("expected BUTTON=KEY"));
    EXPECT_THAT(message("hold-ms=5"), ::testing::HasSubstr("hold-ms is 50 to 5000"));
}

TEST(ButtonReader, AKeyWithOnlyAShortPressPressesAtOnce) {
    FakeEvents events;
    ButtonReader reader(events, six_keys(), "/dev/input/event7");
    events.key(KEY_ENTER, 1, 0);
    events.key(KEY_ENTER, 0, 80);
    events.key(KEY_ESC, 1, 100);
    events.key(KEY_A, 1, 120);  // not mapped
    EXPECT_EQ(reader.read(), (std::vector<Button>{Button::select, Button::back}));
    EXPECT_TRUE(reader.read().empty());
}

TEST(ButtonReader, AutoRepeatRepeatsTheArrowsOnly) {
    FakeEvents events;
    ButtonReader reader(events, six_keys(), "dev");
    events.key(KEY_UP, 1, 0);
    events.key(KEY_UP, 2, 250);
    events.key(KEY_UP, 2, 283);
    events.key(KEY_ENTER, 1, 300);
    events.key(KEY_ENTER, 2, 550);
    EXPECT_EQ(reader.read(),
              (std::vector<Button>{Button::up, Button::up, Button::up, Button::select}));
}

TEST(ButtonReader, ShortAndLongPressesOfOneKey) {
    FakeEvents events;
    ButtonReader reader(events, ButtonMap::phone(), "dev");
    events.key(KEY_POWER, 1, 1000);
    events.key(KEY_POWER, 0, 1200);  // released early: select
    events.key(KEY_POWER, 1, 2000);
    events.key(KEY_POWER, 0, 2600);  // held: back, on release
    events.key(KEY_VOLUMEUP, 1, 3000);
    events.key(KEY_VOLUMEUP, 2, 3250);  // auto-repeat before the hold time: nothing yet
    events.key(KEY_VOLUMEUP, 2, 3517);  // held long enough: right, once
    events.key(KEY_VOLUMEUP, 2, 3550);
    events.key(KEY_VOLUMEUP, 0, 3600);
    EXPECT_EQ(reader.read(), (std::vector<Button>{Button::select, Button::back, Button::right}));
}

TEST(ButtonReader, AHeldKeyBecomesALongPressWithoutAutoRepeat) {
    FakeEvents events;
    ButtonReader reader(events, ButtonMap::phone(), "dev");
    events.key(KEY_VOLUMEDOWN, 1, 10'000);
    EXPECT_TRUE(reader.read().empty());
    EXPECT_EQ(reader.until_long(milliseconds(10'200)), microseconds(300'000));
    EXPECT_FALSE(reader.expire(milliseconds(10'499)));
    EXPECT_EQ(reader.expire(milliseconds(10'500)), Button::left);
    EXPECT_FALSE(reader.until_long(milliseconds(10'600)));
    events.key(KEY_VOLUMEDOWN, 0, 10'700);
    EXPECT_TRUE(reader.read().empty());  // already fired: the release adds nothing
}

TEST(ButtonReader, AnotherKeyEndsAHoldAsAShortPress) {
    FakeEvents events;
    ButtonReader reader(events, ButtonMap::phone(), "dev");
    events.key(KEY_VOLUMEUP, 1, 0);
    events.key(KEY_POWER, 1, 100);
    events.key(KEY_POWER, 0, 150);
    EXPECT_EQ(reader.read(), (std::vector<Button>{Button::up, Button::select}));
}

TEST(ButtonReader, DroppedEventsAreSyncedAndTheHeldKeyForgotten) {
    FakeEvents events;
    ButtonReader reader(events, ButtonMap::phone(), "dev");
    events.key(KEY_POWER, 1, 0);
    events.replies.push_back({LIBEVDEV_READ_STATUS_SYNC,
                              FakeEvents::event(EV_SYN, SYN_DROPPED, 0, 5),
                              LIBEVDEV_READ_FLAG_NORMAL});
    events.replies.push_back({LIBEVDEV_READ_STATUS_SYNC, FakeEvents::event(EV_KEY, KEY_POWER, 0, 6),
                              LIBEVDEV_READ_FLAG_SYNC});
    events.replies.push_back({-EAGAIN, {}, LIBEVDEV_READ_FLAG_SYNC});
    events.key(KEY_VOLUMEDOWN, 1, 700);
    events.key(KEY_VOLUMEDOWN, 0, 750);
    // The power key's release was lost: no select and no back, only the later press.
    EXPECT_EQ(reader.read(), (std::vector<Button>{Button::down}));
    EXPECT_FALSE(reader.expire(milliseconds(5000)));
}

TEST(ButtonReader, AFailingDeviceIsADeviceErrorNamingIt) {
    FakeEvents events;
    ButtonReader reader(events, ButtonMap::phone(), "/dev/input/event3");
    events.replies.push_back({-ENODEV, {}, LIBEVDEV_READ_FLAG_NORMAL});
    try {
        reader.read();
        FAIL() << "no error";
    } catch (const drivers::DeviceError& error) {
        EXPECT_THAT(error.what(),
                    ::testing::HasSubstr("/dev/input/event3: read failed: No such device"));
    }
}

TEST(EvdevDevice, OpeningSomethingThatIsNoDeviceNamesIt) {
    try {
        editor::EvdevDevice device("/dev/null", false);
        FAIL() << "opened /dev/null";
    } catch (const drivers::DeviceError& error) {
        EXPECT_THAT(error.what(), ::testing::HasSubstr("/dev/null: not an evdev device"));
    }
    EXPECT_THROW(editor::EvdevDevice("/nonexistent/event0", false), drivers::DeviceError);
}

TEST(ButtonReader, WhileTappingThePowerKeyGivesItsPressesAndReleasesWithTheirTimes) {
    // On a phone's map the power key is Select short and Back long: while a rhythm is tapped,
    // held is a note, so it reports when it went down and when it came up, never Back.
    FakeEvents events;
    ButtonReader reader(events, ButtonMap::phone(), "phone");
    reader.set_tapping(true);
    events.key(KEY_POWER, 1, 1000);
    events.key(KEY_POWER, 2, 1600);  // auto-repeat past the hold time: still the same note
    events.key(KEY_POWER, 0, 1800);
    events.key(KEY_VOLUMEUP, 1, 2000);  // another key as ever: a short press is Up, done
    events.key(KEY_VOLUMEUP, 0, 2100);
    const auto read = reader.read_events();
    ASSERT_EQ(read.size(), 3u);
    EXPECT_EQ(read[0], (editor::ButtonEvent{Button::select, milliseconds(1000), false}));
    EXPECT_EQ(read[1], (editor::ButtonEvent{Button::select, milliseconds(1800), true}));
    EXPECT_EQ(read[2], (editor::ButtonEvent{Button::up, milliseconds(2000), false}));
    EXPECT_FALSE(reader.expire(milliseconds(5000)));
    // Tapping over, a long press is Back again.
    reader.set_tapping(false);
    events.key(KEY_POWER, 1, 6000);
    events.key(KEY_POWER, 0, 6700);
    EXPECT_EQ(reader.read(), std::vector<Button>{Button::back});
}

}  // namespace
}  // namespace vibscore
