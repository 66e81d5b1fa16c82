#include "daemon/drivers/module_catalog.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <utility>

#include "common/log.hpp"
#include "daemon/drivers/external_driver.hpp"
#include "daemon/drivers/module_probe.hpp"
#include "daemon/drivers/module_trust.hpp"

namespace vibscore::drivers {

namespace {

// The "*.so" names of the directory open at `fd`, in order.
std::vector<std::string> module_names(int fd) {
    std::vector<std::string> names;
    const int listed = ::openat(fd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    DIR* directory = listed < 0 ? nullptr : ::fdopendir(listed);
    if (directory == nullptr) {
        if (listed >= 0) {
            ::close(listed);
        }
        return names;
    }
    while (const dirent* entry = ::readdir(directory)) {
        const std::string name = entry->d_name;
        if (name.size() > 3 && name.ends_with(".so")) {
            names.push_back(name);
        }
    }
    ::closedir(directory);
    std::sort(names.begin(), names.end());
    return names;
}

// The "*.so" of a directory that is not used, to name each in the log.
std::vector<std::filesystem::path> module_files(const std::filesystem::path& directory) {
    std::vector<std::filesystem::path> files;
    std::error_code error;
    for (const auto& file : std::filesystem::directory_iterator(directory, error)) {
        if (file.path().extension() == ".so") {
            files.push_back(file.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

bool same_time(const timespec& a, const timespec& b) {
    return a.tv_sec == b.tv_sec && a.tv_nsec == b.tv_nsec;
}

}  // namespace

std::shared_ptr<const ModuleCatalog> ModuleCatalog::scan(const std::filesystem::path& directory,
                                                         const std::vector<std::string>& reserved,
                                                         uid_t daemon_uid) {
    auto catalog = std::make_shared<ModuleCatalog>();
    catalog->directory_ = directory;
    std::error_code error;
    if (directory.empty() || !std::filesystem::is_directory(directory, error)) {
        return catalog;
    }
    const auto refuse = [&](const std::filesystem::path& path, const std::string& reason) {
        log::warning("driver module " + path.string() + " is not loaded: " + reason);
        catalog->refused_.push_back({path, reason});
    };
    catalog->daemon_uid_ = daemon_uid;
    const auto opened = open_trusted_directory(directory, daemon_uid);
    if (!opened.file) {
        for (const auto& file : module_files(directory)) {
            refuse(file, "its directory is not safe: " + opened.refusal);
        }
        if (catalog->refused_.empty()) {
            log::warning("drivers directory " + directory.string() +
                         " is not used: " + opened.refusal);
        }
        return catalog;
    }
    std::vector<TrustedFile> trusted;
    for (const auto& name : module_names(opened.file->fd->get())) {
        auto module = open_trusted_module(opened.file->fd->get(), directory, name, daemon_uid);
        if (module.file) {
            trusted.push_back(std::move(*module.file));
        } else {
            refuse(directory / name, module.refusal);
        }
    }
    const auto probes = probe_modules(trusted);
    for (std::size_t index = 0; index < probes.size(); ++index) {
        const auto& probed = probes[index];
        if (!probed.loaded()) {
            refuse(probed.path, probed.error);
            continue;
        }
        if (std::find(reserved.begin(), reserved.end(), probed.name) != reserved.end()) {
            refuse(probed.path, "\"" + probed.name + "\" is a built-in driver");
            continue;
        }
        if (const auto* taken = catalog->find(probed.name)) {
            refuse(probed.path, "\"" + probed.name + "\" is the name of " + taken->path.string());
            continue;
        }
        const auto& file = trusted[index];
        catalog->modules_.push_back({probed.name, probed.description, probed.path,
                                     file.status.st_dev, file.status.st_ino, file.status.st_mtim,
                                     file});
    }
    std::sort(catalog->modules_.begin(), catalog->modules_.end(),
              [](const auto& a, const auto& b) { return a.name < b.name; });
    return catalog;
}

const ModuleEntry* ModuleCatalog::find(const std::string& name) const {
    const auto found = std::find_if(modules_.begin(), modules_.end(),
                                    [&](const ModuleEntry& entry) { return entry.name == name; });
    return found == modules_.end() ? nullptr : &*found;
}

const RefusedModule* ModuleCatalog::refused_as(const std::string& name) const {
    const auto found = std::find_if(refused_.begin(), refused_.end(),
                                    [&](const RefusedModule& r) { return r.path.stem() == name; });
    return found == refused_.end() ? nullptr : &*found;
}

bool ModuleCatalog::same_module(const ModuleCatalog& other, const std::string& name) const {
    const auto* mine = find(name);
    const auto* theirs = other.find(name);
    return mine != nullptr && theirs != nullptr && mine->path == theirs->path &&
           mine->device == theirs->device && mine->inode == theirs->inode &&
           same_time(mine->modified, theirs->modified);
}

std::unique_ptr<Actuator> ModuleCatalog::open(
    const std::string& name, const std::map<std::string, std::string>& settings) const {
    const auto* entry = find(name);
    if (entry == nullptr) {
        return nullptr;
    }
    std::shared_ptr<DriverModule> module;
    {
        const std::lock_guard lock(mutex_);
        auto& loaded = loaded_[name];
        if (!loaded) {
            loaded = DriverModule::load(entry->file, daemon_uid_);
        }
        module = loaded;
    }
    return open_external_actuator(std::move(module), settings);
}

}  // namespace vibscore::drivers
