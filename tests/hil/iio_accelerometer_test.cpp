// The IIO accelerometer readers (daemon/sensors/iio_accelerometer.*, what `vibscore calibrate`
// records with) against a real kernel IIO device: the kernel's IIO dummy driver made a
// three-axis accelerometer (tests/hil/iio_dummy_accelerometer.hpp), its buffer fed by a sysfs
// trigger, read through /dev/iio:deviceN and its scan_elements; and polled through
// in_accel_*_raw x in_accel_scale.
#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <string>
#include <thread>

#include "common/monotonic_clock.hpp"
#include "common/number_text.hpp"
#include "daemon/sensors/iio_accelerometer.hpp"
#include "daemon/sensors/open_accelerometer.hpp"
#include "tests/hil/iio_dummy_accelerometer.hpp"
#include "tests/hil/kernel_files.hpp"
#include "tests/support/pace.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {
namespace {

namespace fs = std::filesystem;
using Dummy = IioDummyAccelerometer;

// Every attribute the buffered reader may change, with its value now.
std::map<std::string, std::string> attributes(const fs::path& folder) {
    std::map<std::string, std::string> values;
    for (const auto& entry : fs::directory_iterator(folder / "scan_elements")) {
        if (entry.path().filename().string().ends_with("_en")) {
            values["scan_elements/" + entry.path().filename().string()] =
                read_attribute(entry.path());
        }
    }
    for (const char* name : {"buffer/enable", "buffer/length", "current_timestamp_clock",
                             "trigger/current_trigger", "in_sampling_frequency"}) {
        values[name] = read_attribute(folder / name);
    }
    return values;
}

TEST(IioAccelerometer, TheBufferedReaderRecordsTheDummysScansScaledOnTheMonotonicClock) {
    Dummy dummy;
    const auto before_attributes = attributes(dummy.folder());
    // The dummy starts on the realtime clock: the reader must switch it to ours and back.
    // (6.1 shows it as "realtime\n\0", which read_attribute keeps.)
    ASSERT_EQ(before_attributes.at("current_timestamp_clock").rfind("realtime", 0), 0u);

    const auto io = sensors::system_sensor_io();
    ASSERT_TRUE(sensors::is_iio_accelerometer(dummy.folder(), *io));
    const auto reader = sensors::open_iio_accelerometer(dummy.folder(), {}, io);
    EXPECT_NE(reader->describe().find("buffered"), std::string::npos) << reader->describe();
    EXPECT_NE(reader->describe().find(dummy.device().string()), std::string::npos)
        << reader->describe();

    const std::int64_t before = monotonic_now_ns();
    reader->start();
    EXPECT_EQ(read_attribute(dummy.folder() / "buffer/enable"), "1");
    EXPECT_EQ(read_attribute(dummy.folder() / "current_timestamp_clock").rfind("monotonic", 0), 0u);
    // Scans at 500 Hz until the kernel has taken 50 of them into the buffer the reader drains.
    dummy.start_firing(std::chrono::microseconds(2000));
    ASSERT_TRUE(testing::wait_until([&] { return dummy.fired() >= 50; }));
    const unsigned fired = dummy.stop_firing();
    const auto readings = reader->stop();
    const std::int64_t after = monotonic_now_ns();

    // Every scan the trigger asked for, unless the last ones were still in the kernel's
    // handler when the recording stopped.
    ASSERT_GE(readings.size(), fired - 2) << "fired " << fired;
    ASSERT_LE(readings.size(), fired);
    for (std::size_t i = 0; i < readings.size(); ++i) {
        SCOPED_TRACE("scan " + std::to_string(i));
        EXPECT_DOUBLE_EQ(readings[i].x, Dummy::kScanRaw[0] * Dummy::kScale);
        EXPECT_DOUBLE_EQ(readings[i].y, Dummy::kScanRaw[1] * Dummy::kScale);
        EXPECT_DOUBLE_EQ(readings[i].z, Dummy::kScanRaw[2] * Dummy::kScale);
        // Stamped by the kernel when the trigger fired, on CLOCK_MONOTONIC.
        EXPECT_GT(readings[i].t_ns, before);
        EXPECT_LT(readings[i].t_ns, after);
        if (i > 0) {
            EXPECT_GT(readings[i].t_ns, readings[i - 1].t_ns);
        }
    }
    EXPECT_EQ(attributes(dummy.folder()), before_attributes);
}

TEST(IioAccelerometer, ThePolledReaderReadsRawTimesScaleAtTheDevicesSamplingFrequency) {
    Dummy dummy;
    const auto before_attributes = attributes(dummy.folder());
    // Without the character device (as on a sensor with no buffer) the reader polls sysfs.
    sensors::SensorRoots roots;
    roots.dev = ::testing::TempDir() + "no-iio-devices";
    fs::create_directories(roots.dev);
    const auto reader =
        sensors::open_iio_accelerometer(dummy.folder(), roots, sensors::system_sensor_io());
    // The dummy's in_sampling_frequency is shared by direction (every input channel's, the
    // accelerometer's too: Documentation/ABI/testing/sysfs-bus-iio): the reader polls at it,
    // about 3 Hz, rather than read one value many times over.
    const double rate_hz = std::stod(read_attribute(dummy.folder() / "in_sampling_frequency"));
    ASSERT_GT(rate_hz, 0.0);
    EXPECT_NE(reader->describe().find("polled at " + number_text(rate_hz) + " Hz"),
              std::string::npos)
        << reader->describe();
    const std::int64_t before = monotonic_now_ns();
    reader->start();
    // A recording 2.5 periods long (its length, not a wait for something): 2 or 3 readings.
    vibscore::testing::pace_for(
        std::chrono::microseconds(static_cast<std::int64_t>(2.5e6 / rate_hz)));
    const auto readings = reader->stop();
    const std::int64_t after = monotonic_now_ns();
    ASSERT_GE(readings.size(), 2u);
    // Never faster than the device's rate over the time it recorded.
    ASSERT_LE(static_cast<double>(readings.size()),
              static_cast<double>(after - before) * rate_hz / 1e9 + 1.0);
    for (std::size_t i = 0; i < readings.size(); ++i) {
        SCOPED_TRACE("reading " + std::to_string(i));
        EXPECT_DOUBLE_EQ(readings[i].x, Dummy::kPolledRaw * Dummy::kScale);
        EXPECT_DOUBLE_EQ(readings[i].y, Dummy::kPolledRaw * Dummy::kScale);
        EXPECT_DOUBLE_EQ(readings[i].z, Dummy::kPolledRaw * Dummy::kScale);
        EXPECT_GT(readings[i].t_ns, before);
        EXPECT_LT(readings[i].t_ns, after);
        if (i > 0) {
            EXPECT_GT(readings[i].t_ns, readings[i - 1].t_ns);
        }
    }
    EXPECT_EQ(attributes(dummy.folder()), before_attributes);
}

TEST(IioAccelerometer, AutoFindsTheKernelsIioAccelerometer) {
    Dummy dummy;
    const auto found = sensors::open_accelerometer("auto", nullptr);
    ASSERT_NE(found, nullptr);
    EXPECT_NE(found->describe().find(dummy.device().string()), std::string::npos)
        << found->describe();
}

}  // namespace
}  // namespace vibscore::hil
