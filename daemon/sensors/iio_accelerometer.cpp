#include "daemon/sensors/iio_accelerometer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/number_text.hpp"
#include "daemon/sensors/iio_scan.hpp"
#include "daemon/sensors/threaded_recorder.hpp"

namespace vibscore::sensors {

namespace {

namespace fs = std::filesystem;

constexpr const char* kAxes[3] = {"x", "y", "z"};
// The fastest rate asked for: the probe's highest frequencies are a phone LRA's (~250 Hz); more
// only costs CPU.
constexpr double kMostHz = 2000.0;
// Polled without a sampling frequency to go by.
constexpr double kDefaultPollHz = 400.0;

std::optional<double> number_in(const std::optional<std::string>& text) {
    if (!text) {
        return std::nullopt;
    }
    std::istringstream in(*text);
    double value = 0.0;
    if (!(in >> value) || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

// m/s² per unit: in_accel_x_scale, else in_accel_scale.
double scale_of(const fs::path& folder, const char* axis, SensorIo& io) {
    for (const auto& name :
         {std::string("in_accel_") + axis + "_scale", std::string("in_accel_scale")}) {
        if (const auto scale = number_in(io.read_file(folder / name))) {
            if (!(*scale > 0.0)) {
                throw std::runtime_error((folder / name).string() + " = " + number_text(*scale) +
                                         ": a scale must be above 0");
            }
            return *scale;
        }
    }
    throw std::runtime_error(folder.string() + ": no in_accel_" + axis +
                             "_scale or in_accel_scale: the readings cannot be put in m/s\u00b2");
}

double offset_of(const fs::path& folder, const char* axis, SensorIo& io) {
    for (const auto& name :
         {std::string("in_accel_") + axis + "_offset", std::string("in_accel_offset")}) {
        if (const auto offset = number_in(io.read_file(folder / name))) {
            return *offset;
        }
    }
    return 0.0;
}

// The sampling frequency attribute of the accelerometer, and the rates it offers.
struct Frequency {
    std::optional<fs::path> file;
    std::vector<double> available;
    std::optional<std::string> was;
};

// The names the IIO core gives the sampling frequency (Documentation/ABI/testing/sysfs-bus-iio,
// "sampling_frequency"; the prefix follows how the driver shares it, include/linux/iio/iio.h):
// the accelerometer's own (shared by type), one axis's (separate: the driver keeps one rate for
// all three in practice), every input channel's (shared by direction: `in_sampling_frequency`,
// as the kernel's IIO dummy has it), the whole device's. The first one present is the
// accelerometer's; its `_available` list, else the first list of any of them, the rates offered.
constexpr const char* kFrequencyNames[] = {"in_accel_sampling_frequency",
                                           "in_accel_x_sampling_frequency", "in_sampling_frequency",
                                           "sampling_frequency"};

Frequency frequency_of(const fs::path& folder, SensorIo& io) {
    Frequency frequency;
    std::vector<std::string> lists;
    for (const char* name : kFrequencyNames) {
        if (auto value = io.read_file(folder / name)) {
            frequency.file = folder / name;
            frequency.was = std::move(value);
            lists.push_back(std::string(name) + "_available");
            break;
        }
    }
    for (const char* name : kFrequencyNames) {
        lists.push_back(std::string(name) + "_available");
    }
    for (const std::string& name : lists) {
        if (const auto list = io.read_file(folder / name)) {
            std::istringstream in(*list);
            double rate = 0.0;
            while (in >> rate) {
                frequency.available.push_back(rate);
            }
            break;
        }
    }
    return frequency;
}

// The fastest rate on offer up to kMostHz (or the slowest, when all are faster).
std::optional<double> chosen_rate(const Frequency& frequency) {
    std::optional<double> best;
    for (const double rate : frequency.available) {
        if (rate <= kMostHz && (!best || rate > *best)) {
            best = rate;
        }
    }
    if (!best && !frequency.available.empty()) {
        best = *std::min_element(frequency.available.begin(), frequency.available.end());
    }
    return best;
}

std::string device_name(const fs::path& folder, SensorIo& io) {
    const auto name = io.read_file(folder / "name");
    return folder.string() + (name ? " (" + *name + ")" : std::string());
}

class BufferedIio final : public ThreadedRecorder {
  public:
    BufferedIio(fs::path folder, fs::path device, std::shared_ptr<SensorIo> io)
        : folder_(std::move(folder)), device_(std::move(device)), io_(std::move(io)) {
        for (int axis = 0; axis < 3; ++axis) {
            scale_[axis] = scale_of(folder_, kAxes[axis], *io_);
            offset_[axis] = offset_of(folder_, kAxes[axis], *io_);
        }
        name_ = device_name(folder_, *io_);
    }

    std::string describe() const override {
        return device_.string() + " " + name_ + ", buffered" +
               (rate_hz_ > 0.0 ? ", " + number_text(rate_hz_) + " Hz" : std::string());
    }

  private:
    fs::path scan(const std::string& name) const { return folder_ / "scan_elements" / name; }

    ScanChannel channel(const std::string& prefix) {
        const auto type_text = io_->read_file(scan(prefix + "_type"));
        const auto index_text = number_in(io_->read_file(scan(prefix + "_index")));
        if (!type_text || !index_text) {
            throw std::runtime_error(scan(prefix).string() +
                                     ": the scan element has no _type or _index");
        }
        ScanChannel channel;
        channel.type = parse_scan_type(*type_text, scan(prefix + "_type").string());
        channel.index = static_cast<unsigned>(*index_text);
        return channel;
    }

    void enable(const std::string& prefix) {
        const auto path = scan(prefix + "_en");
        const auto was = io_->read_file(path);
        if (was && *was != "1") {
            io_->write_file(path, "1");
            restore_.emplace_back(path, *was);
        }
    }

    void begin() override {
        restore_.clear();
        partial_.clear();
        if (io_->read_file(folder_ / "buffer" / "enable").value_or("0") == "1") {
            throw std::runtime_error(folder_.string() +
                                     ": its buffer is already enabled: another program streams "
                                     "from it (iio-sensor-proxy?); stop it, or name the device "
                                     "so that it is polled");
        }
        auto frequency = frequency_of(folder_, *io_);
        if (const auto rate = chosen_rate(frequency); rate && frequency.file) {
            io_->write_file(*frequency.file, number_text(*rate));
            restore_.emplace_back(*frequency.file, *frequency.was);
        }
        rate_hz_ = number_in(frequency.file ? io_->read_file(*frequency.file) : std::nullopt)
                       .value_or(0.0);
        if (const auto clock = io_->read_file(folder_ / "current_timestamp_clock")) {
            if (*clock != "monotonic") {
                io_->write_file(folder_ / "current_timestamp_clock", "monotonic");
                restore_.emplace_back(folder_ / "current_timestamp_clock", *clock);
            }
            monotonic_stamps_ = true;
        }
        ScanChannel axes[3];
        std::vector<std::string> ours;
        for (int axis = 0; axis < 3; ++axis) {
            const std::string prefix = std::string("in_accel_") + kAxes[axis];
            enable(prefix);
            axes[axis] = channel(prefix);
            ours.push_back(prefix + "_en");
        }
        std::optional<ScanChannel> timestamp;
        if (io_->read_file(scan("in_timestamp_en"))) {
            enable("in_timestamp");
            timestamp = channel("in_timestamp");
            ours.push_back("in_timestamp_en");
        }
        // Channels someone else left enabled take room in every scan.
        std::vector<ScanChannel> others;
        for (const auto& name : io_->list(folder_ / "scan_elements")) {
            if (name.ends_with("_en") && std::find(ours.begin(), ours.end(), name) == ours.end() &&
                io_->read_file(scan(name)).value_or("0") == "1") {
                others.push_back(channel(name.substr(0, name.size() - 3)));
            }
        }
        layout_ = layout_scan(axes, monotonic_stamps_ ? timestamp : std::nullopt, others);
        if (!monotonic_stamps_) {
            layout_.timestamp.reset();  // not on our clock: timed on arrival instead
        }
        for (int axis = 0; axis < 3; ++axis) {
            layout_.scale[axis] = scale_[axis];
            layout_.offset[axis] = offset_[axis];
        }
        if (const auto length = io_->read_file(folder_ / "buffer" / "length")) {
            if (number_in(length).value_or(0.0) < 1024.0) {
                io_->write_file(folder_ / "buffer" / "length", "1024");
                restore_.emplace_back(folder_ / "buffer" / "length", *length);
            }
        }
        stream_ = io_->open_device(device_);
        io_->write_file(folder_ / "buffer" / "enable", "1");
        enabled_ = true;
    }

    void read_some(std::vector<Reading>& readings) override {
        const auto bytes = stream_->read(std::chrono::milliseconds(50));
        partial_.insert(partial_.end(), bytes.begin(), bytes.end());
        auto decoded = decode_scans(partial_, layout_);
        if (!layout_.timestamp && !decoded.empty()) {
            // Timed on arrival: the last scan now, the ones before it a period apart.
            const std::int64_t now = io_->now_ns();
            const double period_ns = rate_hz_ > 0.0 ? 1e9 / rate_hz_ : 0.0;
            for (std::size_t i = 0; i < decoded.size(); ++i) {
                decoded[i].t_ns =
                    now - static_cast<std::int64_t>(std::llround(
                              static_cast<double>(decoded.size() - 1 - i) * period_ns));
            }
        }
        readings.insert(readings.end(), decoded.begin(), decoded.end());
    }

    void end() noexcept override {
        if (enabled_) {
            try {
                io_->write_file(folder_ / "buffer" / "enable", "0");
            } catch (const std::exception&) {
                // The device may have gone; nothing else to put back there.
            }
            enabled_ = false;
        }
        stream_.reset();
        for (auto it = restore_.rbegin(); it != restore_.rend(); ++it) {
            try {
                io_->write_file(it->first, it->second);
            } catch (const std::exception&) {
                // Best effort: one attribute that will not go back does not stop the others.
            }
        }
        restore_.clear();
    }

    fs::path folder_;
    fs::path device_;
    std::shared_ptr<SensorIo> io_;
    std::string name_;
    double scale_[3] = {1, 1, 1};
    double offset_[3] = {0, 0, 0};
    double rate_hz_ = 0.0;
    bool monotonic_stamps_ = false;
    bool enabled_ = false;
    ScanLayout layout_;
    std::unique_ptr<SensorDevice> stream_;
    std::vector<std::uint8_t> partial_;
    std::vector<std::pair<fs::path, std::string>> restore_;  // what to put back, in order
};

class PolledIio final : public ThreadedRecorder {
  public:
    PolledIio(fs::path folder, std::shared_ptr<SensorIo> io)
        : folder_(std::move(folder)), io_(std::move(io)) {
        for (int axis = 0; axis < 3; ++axis) {
            scale_[axis] = scale_of(folder_, kAxes[axis], *io_);
            offset_[axis] = offset_of(folder_, kAxes[axis], *io_);
        }
        name_ = device_name(folder_, *io_);
        const auto frequency = frequency_of(folder_, *io_);
        rate_hz_ = std::clamp(number_in(frequency.was).value_or(kDefaultPollHz), 1.0, kMostHz);
    }

    std::string describe() const override {
        return name_ + ", polled at " + number_text(rate_hz_) + " Hz";
    }

  private:
    void begin() override { next_ns_ = io_->now_ns(); }

    void read_some(std::vector<Reading>& readings) override {
        const std::int64_t now = io_->now_ns();
        if (now < next_ns_) {
            std::this_thread::sleep_for(std::chrono::nanoseconds(next_ns_ - now));
        }
        next_ns_ += static_cast<std::int64_t>(1e9 / rate_hz_);
        Reading reading;
        reading.t_ns = io_->now_ns();
        double* values[3] = {&reading.x, &reading.y, &reading.z};
        for (int axis = 0; axis < 3; ++axis) {
            const auto file = folder_ / (std::string("in_accel_") + kAxes[axis] + "_raw");
            const auto raw = number_in(io_->read_file(file));
            if (!raw) {
                throw std::runtime_error(file.string() + ": gone or not a number");
            }
            *values[axis] = (*raw + offset_[axis]) * scale_[axis];
        }
        readings.push_back(reading);
    }

    void end() noexcept override {}

    fs::path folder_;
    std::shared_ptr<SensorIo> io_;
    std::string name_;
    double scale_[3] = {1, 1, 1};
    double offset_[3] = {0, 0, 0};
    double rate_hz_ = kDefaultPollHz;
    std::int64_t next_ns_ = 0;
};

}  // namespace

bool is_iio_accelerometer(const fs::path& folder, SensorIo& io) {
    for (const char* axis : kAxes) {
        const std::string raw = std::string("in_accel_") + axis + "_raw";
        const std::string en = std::string("scan_elements/in_accel_") + axis + "_en";
        if (!io.read_file(folder / raw) && !io.read_file(folder / en)) {
            return false;
        }
    }
    return true;
}

std::unique_ptr<Accelerometer> open_iio_accelerometer(const fs::path& folder,
                                                      const SensorRoots& roots,
                                                      std::shared_ptr<SensorIo> io) {
    if (!is_iio_accelerometer(folder, *io)) {
        throw std::runtime_error(folder.string() +
                                 ": not an IIO accelerometer (no in_accel_x, _y and _z, raw or "
                                 "as scan elements)");
    }
    const fs::path device = roots.dev / folder.filename();
    const auto devices = io->list(roots.dev);
    const bool buffered =
        io->read_file(folder / "scan_elements" / "in_accel_x_en") &&
        io->read_file(folder / "buffer" / "enable") &&
        std::find(devices.begin(), devices.end(), folder.filename().string()) != devices.end();
    if (buffered) {
        return std::make_unique<BufferedIio>(folder, device, std::move(io));
    }
    return std::make_unique<PolledIio>(folder, std::move(io));
}

}  // namespace vibscore::sensors
