#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "daemon/drivers/actuator.hpp"

struct vibscore_driver;

namespace vibscore::drivers {

// One loaded driver module (include/vibscore/driver.h); unloaded when the last user goes.
class DriverModule {
  public:
    // Loads `path` and checks its entry point and ABI version. Throws std::runtime_error
    // naming the file and what is wrong with it.
    static std::shared_ptr<DriverModule> load(const std::filesystem::path& path);

    struct Loaded {  // only load() can make one: a module is always a checked one
      private:
        friend class DriverModule;
        Loaded() = default;
    };
    DriverModule(Loaded, std::filesystem::path path, void* handle, const vibscore_driver* entry);
    ~DriverModule();
    DriverModule(const DriverModule&) = delete;
    DriverModule& operator=(const DriverModule&) = delete;

    const vibscore_driver& entry() const { return *entry_; }
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
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
