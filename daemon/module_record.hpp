#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

// A driver module that crashes must not crash the daemon on every start (Restart=on-failure):
// while one drives the actuator, a file in the store names it, and only a clean close removes
// it. A daemon that finds the file at start ended without closing the module (a crash in it, a
// hang the watchdog ended, a kill), and starts with the sim driver instead (docs/drivers.md).
namespace vibscore::daemon {

// The store's file that names the driver module in use.
inline constexpr const char* kModuleRecordFile = ".driver-module";

struct ModuleInUse {
    std::string name;
    std::filesystem::path path;
};

// What the record at `file` says; nullopt when there is none (or it is not one).
std::optional<ModuleInUse> read_module_record(const std::filesystem::path& file);
// Removes the record at `file`, if any.
void remove_module_record(const std::filesystem::path& file);

// Writes the record (crash-safely) when made, removes it when destroyed. An empty `file` keeps
// none (--safe-off, which must leave the record for the next start, and tests). A record that
// cannot be written is a warning: the module still runs, without the fallback.
class ModuleRecord {
  public:
    ModuleRecord(std::filesystem::path file, const ModuleInUse& module);
    ~ModuleRecord();
    ModuleRecord(ModuleRecord&& other) noexcept : file_(std::move(other.file_)) {
        other.file_.clear();
    }
    ModuleRecord(const ModuleRecord&) = delete;
    ModuleRecord& operator=(const ModuleRecord&) = delete;
    ModuleRecord& operator=(ModuleRecord&&) = delete;

  private:
    std::filesystem::path file_;
};

}  // namespace vibscore::daemon
