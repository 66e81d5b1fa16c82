#pragma once

#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/module_trust.hpp"

namespace vibscore::drivers {

class DriverModule;

// A driver module found in the drivers directory that loaded in its trial (module_probe.hpp).
struct ModuleEntry {
    std::string name;
    std::string description;
    std::filesystem::path path;
    // The file that was tried (what a symlink named), so that a reload can tell a replaced
    // module from the one running.
    dev_t device = 0;
    ino_t inode = 0;
    timespec modified{};
    // Open from the scan to the load: the daemon loads this descriptor, the file that was
    // checked and tried, whatever is renamed into its place since (module_trust.hpp).
    TrustedFile file;
};

// A file or directory that is not loaded, and why ("... is writable by group or others (mode
// 0666)", "crashed while loading (SIGSEGV)").
struct RefusedModule {
    std::filesystem::path path;
    std::string reason;
};

// The driver modules of a drivers directory, found once (at start and on each reload) and
// listed from then on without loading anything: a module's constructors run in a trial child
// at the scan and in the daemon only when its driver is opened, once per scan.
class ModuleCatalog {
  public:
    ModuleCatalog() = default;  // no modules

    // Finds the "*.so" of `directory`, each opened once (module_trust.hpp). Refuses, with a
    // warning in the log that names the file and why: a directory or file that someone other
    // than root or `daemon_uid` owns or may write, a link that leads out of `directory`, a module
    // that does not load within kModuleProbeTimeout in its trial or crashes or fails the entry
    // checks, one named as a `reserved` (built-in) driver, and a second module of a name already
    // taken. A missing directory has no modules.
    static std::shared_ptr<const ModuleCatalog> scan(const std::filesystem::path& directory,
                                                     const std::vector<std::string>& reserved,
                                                     uid_t daemon_uid = ::geteuid());

    const std::filesystem::path& directory() const { return directory_; }
    // In name order.
    const std::vector<ModuleEntry>& modules() const { return modules_; }
    const std::vector<RefusedModule>& refused() const { return refused_; }

    const ModuleEntry* find(const std::string& name) const;
    // The refused file driver `name` most likely was: NAME.so, whose name a refused module never
    // got to tell.
    const RefusedModule* refused_as(const std::string& name) const;
    // Whether driver `name` is the same file here and in `other` (both have it, unchanged).
    bool same_module(const ModuleCatalog& other, const std::string& name) const;

    // Opens driver `name` with its settings: its module is loaded into the daemon the first
    // time (then kept while this catalog or an actuator of it lives). nullptr when no module
    // here has that name. Throws DeviceError with the module's message when its open() fails,
    // std::runtime_error when it no longer loads or its file changed since the scan.
    std::unique_ptr<Actuator> open(const std::string& name,
                                   const std::map<std::string, std::string>& settings) const;

  private:
    std::filesystem::path directory_;
    uid_t daemon_uid_ = 0;
    std::vector<ModuleEntry> modules_;
    std::vector<RefusedModule> refused_;
    mutable std::mutex mutex_;
    mutable std::map<std::string, std::shared_ptr<DriverModule>> loaded_;  // by name
};

}  // namespace vibscore::drivers
