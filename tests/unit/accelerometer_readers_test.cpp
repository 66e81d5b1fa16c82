// The accelerometer readers behind sensors::Accelerometer (docs/drivers.md, "Calibrating"),
// against a fake kernel (tests/fakes/fake_sensor_io.hpp): IIO scan types and layouts, the
// buffered and polled IIO readers, the evdev reader, and how [calibration] accelerometer = auto
// chooses among them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <linux/input.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "daemon/sensors/evdev_accelerometer.hpp"
#include "daemon/sensors/iio_accelerometer.hpp"
#include "daemon/sensors/iio_scan.hpp"
#include "daemon/sensors/open_accelerometer.hpp"
#include "tests/fakes/fake_sensor_io.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using sensors::parse_scan_type;
using ::testing::ElementsAre;
using testing::FakeSensorIo;
using ::testing::HasSubstr;

const std::string kIio = "/sys/bus/iio/devices/iio:device0";
const std::string kChar = "/dev/iio:device0";

// Waits for a condition a reader's thread brings about; false after two seconds.
bool eventually(const std::function<bool()>& condition) {
    return testing::wait_until(condition, std::chrono::seconds(2));
}

sensors::SensorRoots roots() {
    return {};
}

TEST(IioScanType, ReadsEndiannessSignBitsStorageShiftAndRepeat) {
    const auto type = parse_scan_type("le:s12/16>>4", "t");
    EXPECT_FALSE(type.big_endian);
    EXPECT_TRUE(type.is_signed);
    EXPECT_EQ(type.bits, 12u);
    EXPECT_EQ(type.storage, 16u);
    EXPECT_EQ(type.shift, 4u);
    EXPECT_EQ(type.repeat, 1u);
    const auto big = parse_scan_type("be:u16/16>>0", "t");
    EXPECT_TRUE(big.big_endian);
    EXPECT_FALSE(big.is_signed);
    EXPECT_EQ(parse_scan_type("le:s16/16X2>>0", "t").repeat, 2u);
    EXPECT_EQ(parse_scan_type("le:s64/64>>0", "t").storage, 64u);
}

TEST(IioScanType, BitsAndShiftFillingTheStorageExactlyAreTakenOneMoreIsRefused) {
    EXPECT_NO_THROW(parse_scan_type("le:s12/16>>4", "t"));
    EXPECT_THROW(parse_scan_type("le:s13/16>>4", "t"), std::invalid_argument);
}

TEST(IioScanType, MalformedTypesAreRefusedNamingWhereAndTheText) {
    try {
        parse_scan_type("xe:s12/16>>4", "scan_elements/in_accel_x_type");
        FAIL();
    } catch (const std::invalid_argument& error) {
        EXPECT_THAT(error.what(), HasSubstr("scan_elements/in_accel_x_type"));
        EXPECT_THAT(error.what(), HasSubstr("xe:s12/16>>4"));
    }
    EXPECT_THROW(parse_scan_type("le:s12/24>>0", "t"), std::invalid_argument);  // no 24-bit storage
    EXPECT_THROW(parse_scan_type("le:s12/16", "t"), std::invalid_argument);
    EXPECT_THROW(parse_scan_type("le:f12/16>>0", "t"), std::invalid_argument);
    EXPECT_THROW(parse_scan_type("le:s12/16>>0 ", "t"), std::invalid_argument);
    EXPECT_THROW(parse_scan_type("le:s0/16>>0", "t"), std::invalid_argument);
}

TEST(IioScanValue, SignExtendsShiftedDataOfEitherEndianness) {
    const auto type = parse_scan_type("le:s12/16>>4", "t");
    const std::uint8_t minus_one[] = {0xF0, 0xFF};  // 0xFFF0 >> 4 = 0xFFF: -1 in 12 bits
    EXPECT_EQ(sensors::scan_value(minus_one, type), -1);
    const std::uint8_t most[] = {0xF0, 0x7F};  // 0x7FF: the largest 12-bit value
    EXPECT_EQ(sensors::scan_value(most, type), 2047);
    const auto big = parse_scan_type("be:u16/16>>0", "t");
    const std::uint8_t value[] = {0x12, 0x34};
    EXPECT_EQ(sensors::scan_value(value, big), 0x1234);
}

TEST(IioScanLayout, ChannelsAreAlignedToTheirStorageAndTheScanPaddedToTheLargest) {
    sensors::ScanChannel axes[3];
    for (unsigned i = 0; i < 3; ++i) {
        axes[i].type = parse_scan_type("le:s16/16>>0", "t");
        axes[i].index = i;
    }
    sensors::ScanChannel timestamp;
    timestamp.type = parse_scan_type("le:s64/64>>0", "t");
    timestamp.index = 3;
    const auto layout = sensors::layout_scan(axes, timestamp);
    EXPECT_EQ(layout.axes[0].offset, 0u);
    EXPECT_EQ(layout.axes[1].offset, 2u);
    EXPECT_EQ(layout.axes[2].offset, 4u);
    EXPECT_EQ(layout.timestamp->offset, 8u);
    EXPECT_EQ(layout.size, 16u);
    // Without the timestamp: three 16-bit channels, 6 bytes.
    EXPECT_EQ(sensors::layout_scan(axes, std::nullopt).size, 6u);
}

TEST(IioScanLayout, IndexOrderNotNameOrderPlacesTheChannels) {
    sensors::ScanChannel axes[3];
    for (unsigned i = 0; i < 3; ++i) {
        axes[i].type = parse_scan_type("le:s16/16>>0", "t");
        axes[i].index = 2 - i;  // z first in the scan
    }
    const auto layout = sensors::layout_scan(axes, std::nullopt);
    EXPECT_EQ(layout.axes[2].offset, 0u);
    EXPECT_EQ(layout.axes[0].offset, 4u);
}

// An IIO accelerometer with a buffer: 16-bit axes at indexes 0..2 and the timestamp at 3; its
// sampling frequency under `frequency` (an empty name: none), the rates on offer under
// `available` (the same name with `_available`, or another).
void add_buffered_device(FakeSensorIo& io, const std::string& frequency = "sampling_frequency",
                         const std::string& available = "sampling_frequency_available") {
    io.file(kIio + "/name", "lsm6dsl_accel");
    io.file(kIio + "/in_accel_scale", "0.000598");
    if (!frequency.empty()) {
        io.file(kIio + "/" + frequency, "104");
    }
    if (!available.empty()) {
        io.file(kIio + "/" + available, "12.5 26 52 104 208 416 833 1666 3332 6664");
    }
    io.file(kIio + "/current_timestamp_clock", "realtime");
    io.file(kIio + "/buffer/enable", "0");
    io.file(kIio + "/buffer/length", "2");
    for (const std::string axis : {"x", "y", "z"}) {
        io.file(kIio + "/scan_elements/in_accel_" + axis + "_en", "0");
        io.file(kIio + "/scan_elements/in_accel_" + axis + "_type", "le:s16/16>>0");
        io.file(kIio + "/scan_elements/in_accel_" + axis + "_index", std::to_string(axis[0] - 'x'));
    }
    io.file(kIio + "/scan_elements/in_timestamp_en", "0");
    io.file(kIio + "/scan_elements/in_timestamp_type", "le:s64/64>>0");
    io.file(kIio + "/scan_elements/in_timestamp_index", "3");
    io.device(kChar);
}

std::vector<std::uint8_t> scan(std::int16_t x, std::int16_t y, std::int16_t z, std::int64_t t) {
    std::vector<std::uint8_t> bytes(16, 0);
    std::memcpy(bytes.data(), &x, 2);
    std::memcpy(bytes.data() + 2, &y, 2);
    std::memcpy(bytes.data() + 4, &z, 2);
    std::memcpy(bytes.data() + 8, &t, 8);
    return bytes;
}

TEST(IioBuffered, RecordsScaledScansWithTheirMonotonicTimesAndPutsTheDeviceBack) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io);
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    reader->start();
    EXPECT_EQ(io->value(kIio + "/buffer/enable"), "1");
    EXPECT_EQ(io->value(kIio + "/sampling_frequency"), "1666");  // the fastest up to 2 kHz
    EXPECT_EQ(io->value(kIio + "/current_timestamp_clock"), "monotonic");
    EXPECT_EQ(io->value(kIio + "/scan_elements/in_accel_y_en"), "1");
    // A scan split across two reads is put together.
    auto first = scan(1000, -1000, 16384, 5'000'000'000);
    auto second = scan(0, 0, -16384, 5'000'600'000);
    std::vector<std::uint8_t> head(second.begin(), second.begin() + 5);
    std::vector<std::uint8_t> tail(second.begin() + 5, second.end());
    first.insert(first.end(), head.begin(), head.end());
    io->feed(kChar, first);
    io->feed(kChar, tail);
    ASSERT_TRUE(eventually([&] { return io->drained(kChar); }));
    const auto readings = reader->stop();
    ASSERT_EQ(readings.size(), 2u);
    EXPECT_EQ(readings[0].t_ns, 5'000'000'000);
    EXPECT_NEAR(readings[0].x, 1000 * 0.000598, 1e-12);
    EXPECT_NEAR(readings[0].y, -1000 * 0.000598, 1e-12);
    EXPECT_NEAR(readings[0].z, 16384 * 0.000598, 1e-12);
    EXPECT_EQ(readings[1].t_ns, 5'000'600'000);
    EXPECT_NEAR(readings[1].z, -16384 * 0.000598, 1e-12);
    // Everything as it was found.
    EXPECT_EQ(io->value(kIio + "/buffer/enable"), "0");
    EXPECT_EQ(io->value(kIio + "/sampling_frequency"), "104");
    EXPECT_EQ(io->value(kIio + "/current_timestamp_clock"), "realtime");
    EXPECT_EQ(io->value(kIio + "/buffer/length"), "2");
    EXPECT_EQ(io->value(kIio + "/scan_elements/in_accel_x_en"), "0");
    EXPECT_EQ(io->value(kIio + "/scan_elements/in_timestamp_en"), "0");
    EXPECT_THAT(reader->describe(), HasSubstr("lsm6dsl_accel"));
    EXPECT_THAT(reader->describe(), HasSubstr("buffered, 1666 Hz"));
}

TEST(IioBuffered, AnAxisAlreadyEnabledIsLeftEnabledAndPerAxisScalesWin) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io);
    io->file(kIio + "/scan_elements/in_accel_z_en", "1");
    io->file(kIio + "/in_accel_z_scale", "0.01");
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    reader->start();
    io->feed(kChar, scan(100, 100, 100, 1));
    ASSERT_TRUE(eventually([&] { return io->drained(kChar); }));
    const auto readings = reader->stop();
    ASSERT_EQ(readings.size(), 1u);
    EXPECT_NEAR(readings[0].x, 100 * 0.000598, 1e-12);
    EXPECT_NEAR(readings[0].z, 1.0, 1e-12);
    EXPECT_EQ(io->value(kIio + "/scan_elements/in_accel_z_en"), "1");
    for (const auto& write : io->writes()) {
        EXPECT_THAT(write, ::testing::Not(HasSubstr("in_accel_z_en"))) << write;
    }
}

TEST(IioBuffered, ABufferSomeoneElseStreamsFromIsRefusedAndNothingIsTouched) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io);
    io->file(kIio + "/buffer/enable", "1");
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    try {
        reader->start();
        FAIL();
    } catch (const std::runtime_error& error) {
        EXPECT_THAT(error.what(), HasSubstr("already enabled"));
    }
    EXPECT_TRUE(io->writes().empty());
}

TEST(IioBuffered, AFailedEnableLeavesEveryChangedAttributeAsItWas) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io);
    io->refuse_writes(kIio + "/buffer/enable");
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    EXPECT_THROW(reader->start(), std::runtime_error);
    EXPECT_EQ(io->value(kIio + "/sampling_frequency"), "104");
    EXPECT_EQ(io->value(kIio + "/scan_elements/in_accel_x_en"), "0");
    EXPECT_EQ(io->value(kIio + "/current_timestamp_clock"), "realtime");
}

TEST(IioBuffered, ADeviceThatGoesAwayFailsTheRecordingNamingItAndIsPutBack) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io);
    io->device(kChar).gone = true;  // unplugged as the recording starts
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    reader->start();
    try {
        reader->stop();
        FAIL() << "stop() returned readings of a device that went away";
    } catch (const std::runtime_error& error) {
        EXPECT_THAT(error.what(), HasSubstr("/dev/iio:device0: the device went away"));
    }
    EXPECT_EQ(io->value(kIio + "/buffer/enable"), "0");
    EXPECT_EQ(io->value(kIio + "/sampling_frequency"), "104");
}

TEST(IioOpen, WithoutAScaleTheReadingsHaveNoUnitAndTheDeviceIsRefused) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io);
    io->file(kIio + "/in_accel_scale", "not a number");
    try {
        sensors::open_iio_accelerometer(kIio, roots(), io);
        FAIL();
    } catch (const std::runtime_error& error) {
        EXPECT_THAT(error.what(), HasSubstr("in_accel_scale"));
    }
}

TEST(IioPolled, WithoutABufferTheRawAttributesAreReadAtTheSamplingFrequency) {
    auto io = std::make_shared<FakeSensorIo>();
    io->file(kIio + "/name", "mma8452");
    io->file(kIio + "/in_accel_x_raw", "10");
    io->file(kIio + "/in_accel_y_raw", "-20");
    io->file(kIio + "/in_accel_z_raw", "1024");
    io->file(kIio + "/in_accel_x_scale", "0.5");
    io->file(kIio + "/in_accel_y_scale", "0.25");
    io->file(kIio + "/in_accel_z_scale", "0.009580");
    io->file(kIio + "/sampling_frequency", "800");
    io->set_now_ns(7'000'000);
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    EXPECT_THAT(reader->describe(), HasSubstr("polled at 800 Hz"));
    reader->start();
    ASSERT_TRUE(eventually([&] { return io->reads(kIio + "/in_accel_z_raw") >= 3; }));
    const auto readings = reader->stop();
    ASSERT_GE(readings.size(), 3u);
    EXPECT_DOUBLE_EQ(readings[0].x, 5.0);
    EXPECT_DOUBLE_EQ(readings[0].y, -5.0);
    EXPECT_NEAR(readings[0].z, 1024 * 0.009580, 1e-12);
    EXPECT_EQ(readings[0].t_ns, 7'000'000);
    EXPECT_TRUE(io->writes().empty());  // polling changes nothing
}

// The names the kernel's IIO ABI gives the sampling frequency, by how the driver shares it
// (Documentation/ABI/testing/sysfs-bus-iio): the buffered reader sets the fastest rate up to
// 2 kHz under whichever the device has, and puts it back.
TEST(IioBuffered, SetsTheSamplingFrequencyUnderEveryNameTheKernelGivesIt) {
    for (const std::string name : {"in_accel_sampling_frequency", "in_accel_x_sampling_frequency",
                                   "in_sampling_frequency", "sampling_frequency"}) {
        SCOPED_TRACE(name);
        auto io = std::make_shared<FakeSensorIo>();
        add_buffered_device(*io, name, name + "_available");
        auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
        reader->start();
        EXPECT_EQ(io->value(kIio + "/" + name), "1666");
        EXPECT_THAT(reader->describe(), HasSubstr("buffered, 1666 Hz"));
        reader->stop();
        EXPECT_EQ(io->value(kIio + "/" + name), "104");
    }
}

TEST(IioBuffered, TheAccelerometersOwnFrequencyComesBeforeTheDirectionsAndTheDevices) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io, "in_accel_sampling_frequency",
                        "in_accel_sampling_frequency_available");
    io->file(kIio + "/in_sampling_frequency", "3.000033");
    io->file(kIio + "/sampling_frequency", "50");
    io->file(kIio + "/sampling_frequency_available", "25 50");
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    reader->start();
    EXPECT_EQ(io->value(kIio + "/in_accel_sampling_frequency"), "1666");
    reader->stop();
    for (const std::string& write : io->writes()) {  // "path=value"
        EXPECT_NE(write.rfind(kIio + "/in_sampling_frequency=", 0), 0u) << write;
        EXPECT_NE(write.rfind(kIio + "/sampling_frequency=", 0), 0u) << write;
    }
}

TEST(IioBuffered, RatesListedOnlyUnderAnotherNameAreStillOffered) {
    // The frequency shared by direction, its list only as the device's.
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io, "in_sampling_frequency", "sampling_frequency_available");
    auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
    reader->start();
    EXPECT_EQ(io->value(kIio + "/in_sampling_frequency"), "1666");
    reader->stop();
    EXPECT_EQ(io->value(kIio + "/in_sampling_frequency"), "104");
}

TEST(IioPolled, ReadsAtTheFrequencySharedByDirectionOrByOneAxis) {
    for (const std::string name : {"in_sampling_frequency", "in_accel_x_sampling_frequency"}) {
        SCOPED_TRACE(name);
        auto io = std::make_shared<FakeSensorIo>();
        io->file(kIio + "/name", "mma8452");
        for (const std::string axis : {"x", "y", "z"}) {
            io->file(kIio + "/in_accel_" + axis + "_raw", "1");
        }
        io->file(kIio + "/in_accel_scale", "0.5");
        io->file(kIio + "/" + name, "833");
        auto reader = sensors::open_iio_accelerometer(kIio, roots(), io);
        EXPECT_THAT(reader->describe(), HasSubstr("polled at 833 Hz"));
    }
}

TEST(IioOpen, AFolderWithoutThreeAccelAxesIsNotAnAccelerometer) {
    auto io = std::make_shared<FakeSensorIo>();
    io->file(kIio + "/name", "gyro");
    io->file(kIio + "/in_anglvel_x_raw", "1");
    io->file(kIio + "/in_accel_x_raw", "1");
    io->file(kIio + "/in_accel_y_raw", "1");
    EXPECT_FALSE(sensors::is_iio_accelerometer(kIio, *io));
    EXPECT_THROW(sensors::open_iio_accelerometer(kIio, roots(), io), std::runtime_error);
}

// An evdev accelerometer at /dev/input/event4, 256 units per g.
void add_evdev(FakeSensorIo& io, const std::string& node, int resolution) {
    auto& device = io.device(node);
    device.properties.insert(INPUT_PROP_ACCELEROMETER);
    for (const unsigned axis : {ABS_X, ABS_Y, ABS_Z}) {
        device.axes[axis] = {-2048, 2047, resolution};
    }
}

std::vector<std::uint8_t> event(std::uint16_t type, std::uint16_t code, std::int32_t value,
                                long usec = 0) {
    input_event e{};
    e.input_event_sec = 12;
    e.input_event_usec = usec;
    e.type = type;
    e.code = code;
    e.value = value;
    std::vector<std::uint8_t> bytes(sizeof e);
    std::memcpy(bytes.data(), &e, sizeof e);
    return bytes;
}

TEST(EvdevAccelerometer, EachSynReportIsAReadingInMetresPerSecondSquaredAtTheEventsTime) {
    auto io = std::make_shared<FakeSensorIo>();
    const std::string node = "/dev/input/event4";
    add_evdev(*io, node, 256);
    auto reader = sensors::open_evdev_accelerometer(node, io);
    reader->start();
    EXPECT_TRUE(io->device(node).monotonic);
    std::vector<std::uint8_t> bytes;
    for (const auto& part :
         {event(EV_ABS, ABS_X, 256), event(EV_ABS, ABS_Z, -128), event(EV_SYN, SYN_REPORT, 0, 500),
          event(EV_ABS, ABS_Y, 512), event(EV_SYN, SYN_REPORT, 0, 1500)}) {
        bytes.insert(bytes.end(), part.begin(), part.end());
    }
    io->feed(node, bytes);
    ASSERT_TRUE(eventually([&] { return io->drained(node); }));
    const auto readings = reader->stop();
    ASSERT_EQ(readings.size(), 2u);
    EXPECT_EQ(readings[0].t_ns, 12'000'500'000);
    EXPECT_DOUBLE_EQ(readings[0].x, 9.80665);
    EXPECT_DOUBLE_EQ(readings[0].z, -9.80665 / 2);
    EXPECT_DOUBLE_EQ(readings[1].x, 9.80665);  // an axis that did not change keeps its value
    EXPECT_DOUBLE_EQ(readings[1].y, 2 * 9.80665);
}

TEST(EvdevAccelerometer, AnAxisWithoutResolutionHasNoUnitAndIsRefused) {
    auto io = std::make_shared<FakeSensorIo>();
    add_evdev(*io, "/dev/input/event4", 0);
    try {
        sensors::open_evdev_accelerometer("/dev/input/event4", io);
        FAIL();
    } catch (const std::runtime_error& error) {
        EXPECT_THAT(error.what(), HasSubstr("no resolution"));
    }
}

TEST(ChoosingTheAccelerometer, AutoTakesIioFirstThenEvdevThenTheBackendsOwn) {
    auto io = std::make_shared<FakeSensorIo>();
    add_evdev(*io, "/dev/input/event4", 256);
    io->device("/dev/input/event1");  // a keyboard: no accelerometer property
    const auto evdev = sensors::open_accelerometer("auto", roots(), io, nullptr);
    ASSERT_NE(evdev, nullptr);
    EXPECT_THAT(evdev->describe(), HasSubstr("/dev/input/event4"));
    add_buffered_device(*io);
    const auto iio = sensors::open_accelerometer("auto", roots(), io, nullptr);
    ASSERT_NE(iio, nullptr);
    EXPECT_THAT(iio->describe(), HasSubstr("iio:device0"));
}

TEST(ChoosingTheAccelerometer, AutoWithNothingFoundIsTheBackendsOwnOrNone) {
    auto io = std::make_shared<FakeSensorIo>();
    EXPECT_EQ(sensors::open_accelerometer("auto", roots(), io, nullptr), nullptr);
    auto io2 = std::make_shared<FakeSensorIo>();
    add_evdev(*io2, "/dev/input/event2", 256);
    std::shared_ptr<sensors::Accelerometer> shared =
        sensors::open_evdev_accelerometer("/dev/input/event2", io2);
    EXPECT_EQ(sensors::open_accelerometer("auto", roots(), io, shared), shared);
}

TEST(ChoosingTheAccelerometer, APathNamesTheDeviceAndAMissingOneIsRefusedByName) {
    auto io = std::make_shared<FakeSensorIo>();
    add_buffered_device(*io);
    EXPECT_THAT(sensors::open_accelerometer(kChar, roots(), io, nullptr)->describe(),
                HasSubstr("lsm6dsl_accel"));
    EXPECT_THAT(sensors::open_accelerometer(kIio, roots(), io, nullptr)->describe(),
                HasSubstr("lsm6dsl_accel"));
    try {
        sensors::open_accelerometer("/dev/iio:device7", roots(), io, nullptr);
        FAIL();
    } catch (const std::runtime_error& error) {
        EXPECT_THAT(error.what(), HasSubstr("/dev/iio:device7: no such IIO device"));
    }
    EXPECT_THROW(sensors::open_accelerometer("/dev/input/event9", roots(), io, nullptr),
                 std::runtime_error);
    EXPECT_THROW(sensors::open_accelerometer("/tmp/accel", roots(), io, nullptr),
                 std::runtime_error);
}

TEST(SystemSensorIo, AnAttributesTextEndsBeforeItsNewlineAndATrailingNul) {
    // Linux 6.1 shows current_timestamp_clock as "realtime\n\0" (seen on the hil guest).
    const std::filesystem::path file = ::testing::TempDir() + "sensor_io_attribute";
    {
        std::ofstream out(file, std::ios::binary);
        out << std::string("realtime\n\0", 10);
    }
    const auto io = sensors::system_sensor_io();
    EXPECT_EQ(io->read_file(file), "realtime");
    {
        std::ofstream out(file, std::ios::binary);
        out << "a b\n";  // what is inside the text stays
    }
    EXPECT_EQ(io->read_file(file), "a b");
    std::filesystem::remove(file);
    EXPECT_EQ(io->read_file(file), std::nullopt);
}

}  // namespace
}  // namespace vibscore
