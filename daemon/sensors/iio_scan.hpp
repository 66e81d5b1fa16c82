#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "daemon/sensors/accelerometer.hpp"

// The IIO buffer's binary format (Documentation/ABI/testing/sysfs-bus-iio, "scan_elements"):
// pure, so every layout a driver may give is tested without a kernel.
namespace vibscore::sensors {

// One channel's in_*_type: "le:s12/16>>4" is little-endian, signed, 12 bits of data in 16 bits
// of storage, shifted right 4; "be:u16/16>>0"; "le:s16/16X2>>0" repeats it twice.
struct ScanType {
    bool big_endian = false;
    bool is_signed = true;
    unsigned bits = 16;     // of data
    unsigned storage = 16;  // bits it occupies: 8, 16, 32 or 64
    unsigned shift = 0;
    unsigned repeat = 1;
};

// Throws std::invalid_argument "`where`: ..." naming the text at fault.
ScanType parse_scan_type(const std::string& text, const std::string& where);

// The raw value of one channel from its storage bytes (sign-extended when signed).
std::int64_t scan_value(const std::uint8_t* bytes, const ScanType& type);

// The channels a scan holds, as their _en, _index and _type say: x, y, z of the accelerometer
// and the timestamp (optional).
struct ScanChannel {
    ScanType type;
    unsigned index = 0;
    std::size_t offset = 0;  // bytes from the scan's start, after alignment
};
struct ScanLayout {
    ScanChannel axes[3];
    std::optional<ScanChannel> timestamp;  // nanoseconds on the device's timestamp clock
    std::size_t size = 0;                  // bytes of one scan, padded
    double scale[3] = {1.0, 1.0, 1.0};     // m/s² per unit, per axis
    double offset[3] = {0.0, 0.0, 0.0};    // added to the raw value before scaling
};

// Places `axes` and the optional timestamp by index order: each aligned to its storage size, the
// scan padded to the largest alignment (the kernel's iio_compute_scan_bytes). Other enabled
// channels (`others`, e.g. a gyroscope left enabled by someone) take their room too.
ScanLayout layout_scan(const ScanChannel (&axes)[3], const std::optional<ScanChannel>& timestamp,
                       const std::vector<ScanChannel>& others = {});

// The readings in `bytes` (whole scans; a trailing partial scan is left in `bytes` for the next
// read). Without a timestamp channel each reading's t_ns is 0: the caller times them.
std::vector<Reading> decode_scans(std::vector<std::uint8_t>& bytes, const ScanLayout& layout);

}  // namespace vibscore::sensors
