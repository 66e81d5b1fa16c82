#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

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

// The crash record above names a module that was driving; a module (or anything else) that
// ends the daemon before it is ready, at every start, is a restart loop it cannot see: a
// constructor that kills the daemon, a scan that crashes it, with driver = sim too. So each start
// is noted in the store until the daemon is ready; a start that finds kFailedStartsForSafeStart
// earlier starts noted within kFailedStartWindow runs driver sim without trying any driver module,
// and logs why. A reload (SIGHUP) tries the configuration again.
inline constexpr const char* kStartRecordFile = ".starts";
inline constexpr int kFailedStartsForSafeStart = 3;
// Above systemd's default restart rate (5 in 10 s) and a slow board's start with a 2 s trial.
inline constexpr std::chrono::seconds kFailedStartWindow{600};

class StartRecord {
  public:
    using Clock = std::chrono::system_clock;

    // Reads `file` (the times of earlier starts that did not become ready) and notes this start
    // at `now`, crash-safely. An empty `file` keeps none; a record that cannot be written is a
    // warning (this start runs unguarded).
    explicit StartRecord(std::filesystem::path file, Clock::time_point now = Clock::now());
    StartRecord(const StartRecord&) = delete;
    StartRecord& operator=(const StartRecord&) = delete;

    // How many earlier starts did not become ready within kFailedStartWindow before now.
    int failed_starts() const { return failed_; }
    // Why this start must run sim without trying the driver modules ("" when it need not).
    std::string safe_start_reason() const;
    // This start is ready (serving): the record goes, and the next start is an ordinary one.
    void ready();

  private:
    std::filesystem::path file_;
    int failed_ = 0;
    Clock::time_point first_{};  // the earliest of those failed starts
    Clock::time_point now_{};
};

}  // namespace vibscore::daemon
