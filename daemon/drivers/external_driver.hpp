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

struct ExternalDriverInfo {
    std::string name;
    std::string description;
    std::filesystem::path path;
};

// The driver modules in `directory` ("*.so"), in name order. A module that does not load is
// left out with a warning naming it; a missing directory has none.
std::vector<ExternalDriverInfo> find_external_drivers(const std::filesystem::path& directory);

// Opens driver `name` from `directory`, or returns nullptr when no module there has that name.
// Throws std::invalid_argument or DeviceError with the driver's own message when open fails.
std::unique_ptr<Actuator> make_external_actuator(
    const std::filesystem::path& directory, const std::string& name,
    const std::map<std::string, std::string>& settings);

}  // namespace vibscore::drivers
