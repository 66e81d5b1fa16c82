#include "daemon/drivers/sysfs_attributes.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>
#include <thread>

#include "common/unique_fd.hpp"
#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

namespace {

DeviceError failure(const std::filesystem::path& path, const std::string& what, int error) {
    return DeviceError(path.string() + ": " + what + ": " + std::strerror(error));
}

class KernelSysfsAttributes final : public SysfsAttributes {
  public:
    void write(const std::filesystem::path& attribute, std::string_view value) override {
        const std::string what = "cannot write \"" + std::string(value) + "\"";
        // No O_CREAT: a missing attribute is an error, not a new file. O_TRUNC matters only
        // for the regular files of a test tree; sysfs ignores it.
        UniqueFd fd(::open(attribute.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC));
        if (fd.get() < 0) {
            throw failure(attribute, what, errno);
        }
        // sysfs takes an attribute in one write; the driver's verdict is that write's result.
        const ssize_t written = ::write(fd.get(), value.data(), value.size());
        if (written < 0) {
            throw failure(attribute, what, errno);
        }
        if (static_cast<std::size_t>(written) != value.size()) {
            throw DeviceError(attribute.string() + ": " + what + ": short write");
        }
        if (const int error = fd.close()) {
            throw failure(attribute, what, error);
        }
    }

    std::string read(const std::filesystem::path& attribute) override {
        UniqueFd fd(::open(attribute.c_str(), O_RDONLY | O_CLOEXEC));
        if (fd.get() < 0) {
            throw failure(attribute, "cannot read", errno);
        }
        // Most attributes fit a page, but an LED's trigger list can be longer: read to the end.
        std::string text;
        char buffer[4096];
        for (;;) {
            const ssize_t length = ::read(fd.get(), buffer, sizeof buffer);
            if (length < 0) {
                throw failure(attribute, "cannot read", errno);
            }
            if (length == 0) {
                break;
            }
            text.append(buffer, static_cast<std::size_t>(length));
        }
        while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
            text.pop_back();
        }
        return text;
    }

    bool exists(const std::filesystem::path& path) override {
        std::error_code error;
        return std::filesystem::exists(path, error);
    }
};

}  // namespace

std::unique_ptr<SysfsAttributes> make_kernel_sysfs_attributes() {
    return std::make_unique<KernelSysfsAttributes>();
}

bool wait_until_exists(SysfsAttributes& attributes, const std::filesystem::path& path,
                       std::chrono::milliseconds timeout) {
    constexpr auto kPoll = std::chrono::milliseconds(10);
    for (auto waited = std::chrono::milliseconds(0);; waited += kPoll) {
        if (attributes.exists(path)) {
            return true;
        }
        if (waited >= timeout) {
            return false;
        }
        std::this_thread::sleep_for(kPoll);
    }
}

}  // namespace vibscore::drivers
