// The evdev accelerometer reader (daemon/sensors/evdev_accelerometer.*, what `vibscore
// calibrate` records with) against the real kernel: a uinput device with
// INPUT_PROP_ACCELEROMETER and ABS_X/Y/Z in units per g, as an IMU's input driver makes one.
#include <gtest/gtest.h>

#include <linux/uinput.h>
#include <unistd.h>

#include <cstring>

#include "common/monotonic_clock.hpp"
#include "daemon/sensors/evdev_accelerometer.hpp"
#include "daemon/sensors/open_accelerometer.hpp"
#include "tests/hil/uinput_device.hpp"

namespace vibscore::hil {
namespace {

constexpr int kUnitsPerG = 256;

void emit(int fd, std::uint16_t type, std::uint16_t code, std::int32_t value) {
    input_event event{};
    event.type = type;
    event.code = code;
    event.value = value;
    ASSERT_EQ(::write(fd, &event, sizeof event), static_cast<ssize_t>(sizeof event));
}

// A uinput accelerometer, kept while this lives.
struct UinputAccelerometer {
    UinputAccelerometer() : fd(open_uinput()) {
        uinput_ioctl(fd.get(), UI_SET_EVBIT, "UI_SET_EVBIT", EV_ABS);
        uinput_ioctl(fd.get(), UI_SET_PROPBIT, "UI_SET_PROPBIT", INPUT_PROP_ACCELEROMETER);
        for (const unsigned axis : {ABS_X, ABS_Y, ABS_Z}) {
            uinput_ioctl(fd.get(), UI_SET_ABSBIT, "UI_SET_ABSBIT", axis);
            uinput_abs_setup abs{};
            abs.code = static_cast<std::uint16_t>(axis);
            abs.absinfo.minimum = -4 * kUnitsPerG;
            abs.absinfo.maximum = 4 * kUnitsPerG;
            abs.absinfo.resolution = kUnitsPerG;
            uinput_ioctl(fd.get(), UI_ABS_SETUP, "UI_ABS_SETUP",
                         reinterpret_cast<unsigned long>(&abs));
        }
        uinput_setup setup{};
        setup.id.bustype = BUS_VIRTUAL;
        std::strcpy(setup.name, "vibscore-test-accelerometer");
        nodes = create_uinput_device(fd.get(), setup);
    }
    UniqueFd fd;
    UinputNodes nodes;
};

TEST(AccelerometerSmoke, TheEvdevReaderRecordsAUinputAccelerometerInMetresPerSecondSquared) {
    UinputAccelerometer device;
    const auto io = sensors::system_sensor_io();
    ASSERT_TRUE(sensors::is_evdev_accelerometer(device.nodes.event_node, *io));
    const auto reader = sensors::open_evdev_accelerometer(device.nodes.event_node, io);
    reader->start();
    const std::int64_t before = monotonic_now_ns();
    emit(device.fd.get(), EV_ABS, ABS_X, kUnitsPerG);
    emit(device.fd.get(), EV_ABS, ABS_Z, -2 * kUnitsPerG);
    emit(device.fd.get(), EV_SYN, SYN_REPORT, 0);
    emit(device.fd.get(), EV_ABS, ABS_Y, kUnitsPerG / 2);
    emit(device.fd.get(), EV_SYN, SYN_REPORT, 0);
    const auto readings = reader->stop();
    const std::int64_t after = monotonic_now_ns();
    ASSERT_EQ(readings.size(), 2u);
    EXPECT_DOUBLE_EQ(readings[0].x, 9.80665);
    EXPECT_DOUBLE_EQ(readings[0].z, -2 * 9.80665);
    EXPECT_DOUBLE_EQ(readings[1].y, 9.80665 / 2);
    EXPECT_DOUBLE_EQ(readings[1].x, 9.80665);  // unchanged axes keep their value
    // Timed by the kernel on CLOCK_MONOTONIC, the daemon's clock (to the microsecond).
    EXPECT_GE(readings[0].t_ns, before - 1000);
    EXPECT_LE(readings[1].t_ns, after);
}

TEST(AccelerometerSmoke, AutoFindsTheUinputAccelerometerAndSkipsOtherInputDevices) {
    UinputAccelerometer device;
    const auto found = sensors::open_accelerometer("auto", nullptr);
    ASSERT_NE(found, nullptr);
    EXPECT_NE(found->describe().find("/dev/input/event"), std::string::npos) << found->describe();
}

}  // namespace
}  // namespace vibscore::hil
