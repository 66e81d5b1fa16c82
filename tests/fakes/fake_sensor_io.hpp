#pragma once

#include <chrono>
#include <cstdint>
#include <cstring>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "daemon/sensors/sensor_io.hpp"

namespace vibscore::testing {

// A fake kernel behind sensors::SensorIo: attributes in memory (a folder exists when a file lies
// under it), writes logged and applied, any attribute made to refuse writes; character devices
// that hand out the bytes a test queued, one chunk a read, and evdev properties and axes. The
// clock is the test's. Shared by the reader and the test (a recording thread reads it too).
class FakeSensorIo : public sensors::SensorIo {
  public:
    struct Device {
        std::deque<std::vector<std::uint8_t>> chunks;
        std::set<unsigned> properties;
        std::map<unsigned, sensors::AbsAxis> axes;
        bool gone = false;
        bool monotonic = false;
        int opened = 0;
    };

    void file(const std::string& path, const std::string& content) {
        const std::lock_guard lock(mutex_);
        files_[path] = content;
    }
    void refuse_writes(const std::string& path) {
        const std::lock_guard lock(mutex_);
        refused_.insert(path);
    }
    std::string value(const std::string& path) {
        const std::lock_guard lock(mutex_);
        const auto found = files_.find(path);
        return found == files_.end() ? "<missing>" : found->second;
    }
    std::vector<std::string> writes() {
        const std::lock_guard lock(mutex_);
        return writes_;
    }
    Device& device(const std::string& path) {
        const std::lock_guard lock(mutex_);
        return devices_[path];
    }
    // Queues bytes for the device's next read.
    void feed(const std::string& path, std::vector<std::uint8_t> bytes) {
        const std::lock_guard lock(mutex_);
        devices_[path].chunks.push_back(std::move(bytes));
    }
    // Whether every queued chunk has been read.
    bool drained(const std::string& path) {
        const std::lock_guard lock(mutex_);
        return devices_[path].chunks.empty();
    }
    void set_now_ns(std::int64_t now) {
        const std::lock_guard lock(mutex_);
        now_ns_ = now;
    }

    // How many times `path` was read.
    int reads(const std::string& path) {
        const std::lock_guard lock(mutex_);
        return reads_[path];
    }

    std::optional<std::string> read_file(const std::filesystem::path& file) override {
        const std::lock_guard lock(mutex_);
        ++reads_[file.string()];
        const auto found = files_.find(file.string());
        if (found == files_.end()) {
            return std::nullopt;
        }
        return found->second;
    }
    void write_file(const std::filesystem::path& file, const std::string& value) override {
        const std::lock_guard lock(mutex_);
        if (refused_.count(file.string()) != 0 || files_.count(file.string()) == 0) {
            throw std::runtime_error(file.string() + ": cannot write \"" + value +
                                     "\": Permission denied");
        }
        files_[file.string()] = value;
        writes_.push_back(file.string() + "=" + value);
    }
    std::vector<std::string> list(const std::filesystem::path& folder) override {
        const std::lock_guard lock(mutex_);
        std::set<std::string> names;
        const std::string prefix = folder.string() + "/";
        const auto add = [&](const std::string& path) {
            if (path.rfind(prefix, 0) == 0) {
                const auto rest = path.substr(prefix.size());
                names.insert(rest.substr(0, rest.find('/')));
            }
        };
        for (const auto& [path, content] : files_) {
            add(path);
        }
        for (const auto& [path, device] : devices_) {
            add(path);
        }
        return {names.begin(), names.end()};
    }
    std::unique_ptr<sensors::SensorDevice> open_device(const std::filesystem::path& path) override {
        const std::lock_guard lock(mutex_);
        const auto found = devices_.find(path.string());
        if (found == devices_.end()) {
            throw std::runtime_error(path.string() + ": cannot open: No such file or directory");
        }
        ++found->second.opened;
        return std::make_unique<Open>(*this, path.string());
    }
    std::int64_t now_ns() override {
        const std::lock_guard lock(mutex_);
        return now_ns_;
    }

  private:
    class Open final : public sensors::SensorDevice {
      public:
        Open(FakeSensorIo& io, std::string path) : io_(io), path_(std::move(path)) {}
        std::vector<std::uint8_t> read(std::chrono::milliseconds) override {
            const std::lock_guard lock(io_.mutex_);
            auto& device = io_.devices_[path_];
            if (device.gone) {
                throw std::runtime_error(path_ + ": the device went away");
            }
            if (device.chunks.empty()) {
                return {};
            }
            auto chunk = std::move(device.chunks.front());
            device.chunks.pop_front();
            return chunk;
        }
        bool has_input_property(unsigned property) override {
            const std::lock_guard lock(io_.mutex_);
            return io_.devices_[path_].properties.count(property) != 0;
        }
        std::optional<sensors::AbsAxis> abs_axis(unsigned code) override {
            const std::lock_guard lock(io_.mutex_);
            const auto& axes = io_.devices_[path_].axes;
            const auto found = axes.find(code);
            return found == axes.end() ? std::nullopt : std::optional(found->second);
        }
        void use_monotonic_clock() override {
            const std::lock_guard lock(io_.mutex_);
            io_.devices_[path_].monotonic = true;
        }

      private:
        FakeSensorIo& io_;
        std::string path_;
    };

    std::mutex mutex_;
    std::map<std::string, std::string> files_;
    std::set<std::string> refused_;
    std::vector<std::string> writes_;
    std::map<std::string, Device> devices_;
    std::map<std::string, int> reads_;
    std::int64_t now_ns_ = 0;
};

}  // namespace vibscore::testing
