#include "daemon/module_record.hpp"

#include <exception>
#include <fstream>
#include <utility>

#include "daemon/log.hpp"
#include "daemon/registry/atomic_file.hpp"

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

}  // namespace vibscore::daemon
