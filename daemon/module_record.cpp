#include "daemon/module_record.hpp"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <fstream>
#include <sstream>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/log.hpp"

namespace vibscore::daemon {

std::optional<ModuleInUse> read_module_record(const std::filesystem::path& file) {
    if (file.empty()) {
        return std::nullopt;
    }
    std::ifstream in(file);
    ModuleInUse module;
    std::string path;
    if (!std::getline(in, module.name) || !std::getline(in, path) || module.name.empty()) {
        return std::nullopt;
    }
    module.path = path;
    return module;
}

ModuleRecord::ModuleRecord(std::filesystem::path file, const ModuleInUse& module)
    : file_(std::move(file)) {
    if (file_.empty()) {
        return;
    }
    try {
        write_file_atomically(file_, module.name + "\n" + module.path.string() + "\n", 0644);
    } catch (const std::exception& error) {
        log::warning("driver module " + module.name + ": cannot note it as in use (" +
                     error.what() + "); a crash in it would not be told at the next start");
        file_.clear();
    }
}

void remove_module_record(const std::filesystem::path& file) {
    if (file.empty()) {
        return;
    }
    try {
        remove_file_durably(file);
    } catch (const std::exception& error) {
        log::warning("cannot remove " + file.string() + ": " + error.what());
    }
}

ModuleRecord::~ModuleRecord() {
    remove_module_record(file_);
}

namespace {

std::int64_t seconds_of(StartRecord::Clock::time_point time) {
    return std::chrono::duration_cast<std::chrono::seconds>(time.time_since_epoch()).count();
}

}  // namespace

StartRecord::StartRecord(std::filesystem::path file, Clock::time_point now)
    : file_(std::move(file)), now_(now) {
    if (file_.empty()) {
        return;
    }
    // One start a line, seconds since the epoch; only those within the window are kept.
    std::vector<std::int64_t> kept;
    std::ifstream in(file_);
    const std::int64_t now_s = seconds_of(now);
    for (std::int64_t started = 0; in >> started;) {
        if (started <= now_s && now_s - started < kFailedStartWindow.count()) {
            kept.push_back(started);
        }
    }
    failed_ = static_cast<int>(kept.size());
    if (!kept.empty()) {
        first_ =
            Clock::time_point(std::chrono::seconds(*std::min_element(kept.begin(), kept.end())));
    }
    kept.push_back(now_s);
    std::ostringstream text;
    for (const auto started : kept) {
        text << started << "\n";
    }
    try {
        write_file_atomically(file_, text.str(), 0644);
    } catch (const std::exception& error) {
        log::warning("cannot note this start in " + file_.string() + " (" + error.what() +
                     "); a restart loop before the daemon is ready would not be stopped");
        file_.clear();
    }
}

std::string StartRecord::safe_start_reason() const {
    if (failed_ < kFailedStartsForSafeStart) {
        return {};
    }
    const auto ago = std::chrono::duration_cast<std::chrono::seconds>(now_ - first_);
    return "vibscored's last " + std::to_string(failed_) + " starts ended before it was ready (" +
           file_.string() + ", the first " + std::to_string(ago.count()) +
           " s ago): starting with driver sim and without trying any driver module, so that the "
           "daemon serves; a reload (SIGHUP, systemctl reload vibscored) tries the "
           "configuration again";
}

void StartRecord::ready() {
    remove_module_record(file_);
    file_.clear();
}

}  // namespace vibscore::daemon
