#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace vibscore::drivers {

// The sysfs calls the sysfs backends make: write an attribute, read one, see whether a path is
// there. Tests put a fake kernel behind it (files in a temporary tree plus the side effects of
// export and trigger writes) that can also fail on demand.
class SysfsAttributes {
  public:
    virtual ~SysfsAttributes() = default;

    // Writes `value` to the existing attribute file in one write(). Throws DeviceError naming the
    // path, the value and the errno text (EINVAL, EBUSY, EIO, ENODEV ... come from the driver).
    virtual void write(const std::filesystem::path& attribute, std::string_view value) = 0;

    // The attribute's content without the trailing newline. Throws DeviceError naming the path.
    virtual std::string read(const std::filesystem::path& attribute) = 0;

    virtual bool exists(const std::filesystem::path& path) = 0;
};

// The kernel's sysfs: open, write or read, close.
std::unique_ptr<SysfsAttributes> make_kernel_sysfs_attributes();

// Waits up to `timeout` for `path` to appear (after an export or a trigger change the kernel
// creates it at once, but udev may still be adjusting permissions); true if it did.
bool wait_until_exists(SysfsAttributes& attributes, const std::filesystem::path& path,
                       std::chrono::milliseconds timeout = std::chrono::milliseconds(1000));

}  // namespace vibscore::drivers
