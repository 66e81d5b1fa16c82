#pragma once

#include <unistd.h>
#include <filesystem>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/module_trust.hpp"

struct vibscore_driver;

namespace vibscore::drivers {

// One loaded driver module (include/vibscore/driver.h); unloaded when the last user goes.
class DriverModule {
  public:
    // Loads the file open at `module.fd` (/proc/self/fd/N: never what its name names now) when
    // it is still the file that was checked (changed_since_checked), and checks its entry point
    // and ABI version. Throws std::runtime_error naming the file and what is wrong with it.
    static std::shared_ptr<DriverModule> load(const TrustedFile& module,
                                              uid_t daemon_uid = ::geteuid());
    // Opens `path` as the scan does (open_trusted_module), then loads that.
    static std::shared_ptr<DriverModule> load(const std::filesystem::path& path,
                                              uid_t daemon_uid = ::geteuid());

    struct Loaded {  // only load() can make one: a module is always a checked one
      private:
        friend class DriverModule;
        Loaded() = default;
    };
    DriverModule(Loaded, TrustedFile file, void* handle, const vibscore_driver* entry);
    ~DriverModule();
    DriverModule(const DriverModule&) = delete;
    DriverModule& operator=(const DriverModule&) = delete;

    const vibscore_driver& entry() const { return *entry_; }
    const std::filesystem::path& path() const { return file_.path; }

  private:
    // Open while the loader may know the module by "/proc/self/fd/N", so that no other file
    // gets that number and, by that name, this module's handle.
    TrustedFile file_;
    void* handle_;
    const vibscore_driver* entry_;
};

// What is wrong with the entry point of the loaded module `handle`: "" when nothing is, and
// then `entry` is its vibscore_driver. Checks the symbol, the ABI version, the name
// ([a-z0-9-], 1-64) and that every required function is set.
std::string entry_problem(void* handle, const vibscore_driver*& entry);

// Opens the module's actuator with its settings ("key = value" lines of its section). Throws
// DeviceError with the module's own message when its open() fails.
std::unique_ptr<Actuator> open_external_actuator(
    std::shared_ptr<DriverModule> module, const std::map<std::string, std::string>& settings);

}  // namespace vibscore::drivers
