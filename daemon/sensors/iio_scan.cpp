#include "daemon/sensors/iio_scan.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>

namespace vibscore::sensors {

namespace {

unsigned number_at(const std::string& text, std::size_t& at, const std::string& where) {
    unsigned value = 0;
    const auto* begin = text.data() + at;
    const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
    if (error != std::errc() || end == begin) {
        throw std::invalid_argument(where + ": scan type \"" + text +
                                    "\": expected a number at \"" + text.substr(at) + "\"");
    }
    at += static_cast<std::size_t>(end - begin);
    return value;
}

void expect(const std::string& text, std::size_t& at, const std::string& what,
            const std::string& where) {
    if (text.compare(at, what.size(), what) != 0) {
        throw std::invalid_argument(where + ": scan type \"" + text + "\": expected \"" + what +
                                    "\" at \"" + text.substr(std::min(at, text.size())) + "\"");
    }
    at += what.size();
}

}  // namespace

ScanType parse_scan_type(const std::string& text, const std::string& where) {
    ScanType type;
    std::size_t at = 0;
    if (text.compare(0, 3, "le:") == 0) {
        type.big_endian = false;
    } else if (text.compare(0, 3, "be:") == 0) {
        type.big_endian = true;
    } else {
        throw std::invalid_argument(where + ": scan type \"" + text +
                                    "\": expected le: or be: at the start");
    }
    at = 3;
    if (at < text.size() && (text[at] == 's' || text[at] == 'u')) {
        type.is_signed = text[at] == 's';
        ++at;
    } else {
        throw std::invalid_argument(where + ": scan type \"" + text + "\": expected s or u after " +
                                    text.substr(0, 3));
    }
    type.bits = number_at(text, at, where);
    expect(text, at, "/", where);
    type.storage = number_at(text, at, where);
    if (at < text.size() && text[at] == 'X') {
        ++at;
        type.repeat = number_at(text, at, where);
    }
    expect(text, at, ">>", where);
    type.shift = number_at(text, at, where);
    if (at != text.size()) {
        throw std::invalid_argument(where + ": scan type \"" + text + "\": unexpected \"" +
                                    text.substr(at) + "\" at the end");
    }
    if (type.storage != 8 && type.storage != 16 && type.storage != 32 && type.storage != 64) {
        throw std::invalid_argument(where + ": scan type \"" + text + "\": storage of " +
                                    std::to_string(type.storage) +
                                    " bits (expected 8, 16, 32 or 64)");
    }
    if (type.bits == 0 || type.bits + type.shift > type.storage) {
        throw std::invalid_argument(where + ": scan type \"" + text +
                                    "\": " + std::to_string(type.bits) + " bits shifted by " +
                                    std::to_string(type.shift) + " do not fit in " +
                                    std::to_string(type.storage));
    }
    if (type.repeat == 0) {
        throw std::invalid_argument(where + ": scan type \"" + text + "\": a repeat of 0");
    }
    return type;
}

std::int64_t scan_value(const std::uint8_t* bytes, const ScanType& type) {
    const unsigned size = type.storage / 8;
    std::uint64_t raw = 0;
    for (unsigned i = 0; i < size; ++i) {
        const unsigned byte = type.big_endian ? i : size - 1 - i;
        raw = (raw << 8) | bytes[byte];
    }
    raw >>= type.shift;
    if (type.bits < 64) {
        raw &= (std::uint64_t{1} << type.bits) - 1;
        if (type.is_signed && (raw >> (type.bits - 1)) & 1u) {
            raw |= ~((std::uint64_t{1} << type.bits) - 1);  // sign-extend
        }
    }
    return static_cast<std::int64_t>(raw);
}

ScanLayout layout_scan(const ScanChannel (&axes)[3], const std::optional<ScanChannel>& timestamp,
                       const std::vector<ScanChannel>& others) {
    ScanLayout layout;
    // Every enabled channel, in index order: [0..2] the axes, [3] the timestamp, then the others.
    std::vector<ScanChannel> all(std::begin(axes), std::end(axes));
    if (timestamp) {
        all.push_back(*timestamp);
    }
    all.insert(all.end(), others.begin(), others.end());
    std::vector<std::size_t> order(all.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return all[a].index < all[b].index; });
    std::size_t offset = 0;
    std::size_t largest = 1;
    for (const std::size_t i : order) {
        const std::size_t size = all[i].type.storage / 8;
        const std::size_t length = size * all[i].type.repeat;
        offset = (offset + size - 1) / size * size;  // aligned to its storage size
        all[i].offset = offset;
        offset += length;
        largest = std::max(largest, size);
    }
    layout.size = (offset + largest - 1) / largest * largest;
    for (int axis = 0; axis < 3; ++axis) {
        layout.axes[axis] = all[static_cast<std::size_t>(axis)];
    }
    if (timestamp) {
        layout.timestamp = all[3];
    }
    return layout;
}

std::vector<Reading> decode_scans(std::vector<std::uint8_t>& bytes, const ScanLayout& layout) {
    std::vector<Reading> readings;
    if (layout.size == 0) {
        return readings;
    }
    const std::size_t whole = bytes.size() / layout.size;
    for (std::size_t n = 0; n < whole; ++n) {
        const std::uint8_t* scan = bytes.data() + n * layout.size;
        Reading reading;
        double* values[3] = {&reading.x, &reading.y, &reading.z};
        for (int axis = 0; axis < 3; ++axis) {
            const auto& channel = layout.axes[axis];
            const auto raw = scan_value(scan + channel.offset, channel.type);
            *values[axis] = (static_cast<double>(raw) + layout.offset[axis]) * layout.scale[axis];
        }
        if (layout.timestamp) {
            reading.t_ns = scan_value(scan + layout.timestamp->offset, layout.timestamp->type);
        }
        readings.push_back(reading);
    }
    bytes.erase(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(whole * layout.size));
    return readings;
}

}  // namespace vibscore::sensors
