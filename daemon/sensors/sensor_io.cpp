#include "daemon/sensors/sensor_io.hpp"

#include <fcntl.h>
#include <linux/input.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/monotonic_clock.hpp"
#include "common/unique_fd.hpp"

namespace vibscore::sensors {

namespace {

std::string failure(const std::string& what, const std::filesystem::path& path) {
    return path.string() + ": " + what + ": " + std::strerror(errno);
}

class SystemDevice final : public SensorDevice {
  public:
    explicit SystemDevice(const std::filesystem::path& path)
        : path_(path), fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)) {
        if (fd_.get() < 0) {
            throw std::runtime_error(failure("cannot open", path));
        }
    }

    std::vector<std::uint8_t> read(std::chrono::milliseconds timeout) override {
        pollfd ready{fd_.get(), POLLIN, 0};
        const int polled = ::poll(&ready, 1, static_cast<int>(timeout.count()));
        if (polled < 0 && errno != EINTR) {
            throw std::runtime_error(failure("poll", path_));
        }
        std::vector<std::uint8_t> bytes;
        if (polled <= 0) {
            return bytes;
        }
        if (ready.revents & (POLLERR | POLLHUP | POLLNVAL)) {
            throw std::runtime_error(path_.string() + ": the device went away");
        }
        std::uint8_t chunk[8192];
        for (;;) {
            const ssize_t got = ::read(fd_.get(), chunk, sizeof chunk);
            if (got > 0) {
                bytes.insert(bytes.end(), chunk, chunk + got);
                continue;
            }
            if (got < 0 && errno != EAGAIN && errno != EINTR) {
                throw std::runtime_error(failure("read", path_));
            }
            return bytes;
        }
    }

    bool has_input_property(unsigned property) override {
        std::uint8_t bits[INPUT_PROP_CNT / 8 + 1] = {};
        if (::ioctl(fd_.get(), EVIOCGPROP(sizeof bits), bits) < 0) {
            return false;
        }
        return property < INPUT_PROP_CNT && (bits[property / 8] >> (property % 8)) & 1u;
    }

    std::optional<AbsAxis> abs_axis(unsigned code) override {
        input_absinfo info{};
        if (::ioctl(fd_.get(), EVIOCGABS(code), &info) < 0) {
            return std::nullopt;
        }
        return AbsAxis{info.minimum, info.maximum, info.resolution};
    }

    void use_monotonic_clock() override {
        int clock = CLOCK_MONOTONIC;
        if (::ioctl(fd_.get(), EVIOCSCLOCKID, &clock) < 0) {
            throw std::runtime_error(failure("EVIOCSCLOCKID", path_));
        }
    }

  private:
    std::filesystem::path path_;
    UniqueFd fd_;
};

class SystemIo final : public SensorIo {
  public:
    std::optional<std::string> read_file(const std::filesystem::path& file) override {
        std::error_code error;
        if (!std::filesystem::exists(file, error)) {
            return std::nullopt;
        }
        std::ifstream in(file);
        if (!in) {
            throw std::runtime_error(failure("cannot open", file));
        }
        std::ostringstream text;
        text << in.rdbuf();
        std::string content = text.str();
        // Some attributes end in a NUL after the newline (6.1's current_timestamp_clock shows
        // "realtime\n\0"): text ends there.
        while (!content.empty() &&
               (content.back() == '\n' || content.back() == ' ' || content.back() == '\0')) {
            content.pop_back();
        }
        return content;
    }

    void write_file(const std::filesystem::path& file, const std::string& value) override {
        const UniqueFd fd(::open(file.c_str(), O_WRONLY | O_CLOEXEC));
        if (fd.get() < 0 || ::write(fd.get(), value.data(), value.size()) < 0) {
            throw std::runtime_error(failure("cannot write \"" + value + "\"", file));
        }
    }

    std::vector<std::string> list(const std::filesystem::path& folder) override {
        std::vector<std::string> names;
        std::error_code error;
        for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    std::unique_ptr<SensorDevice> open_device(const std::filesystem::path& device) override {
        return std::make_unique<SystemDevice>(device);
    }

    std::int64_t now_ns() override { return monotonic_now_ns(); }
};

}  // namespace

std::shared_ptr<SensorIo> system_sensor_io() {
    return std::make_shared<SystemIo>();
}

}  // namespace vibscore::sensors
