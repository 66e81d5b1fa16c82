#include "daemon/drivers/module_trust.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace vibscore::drivers {

namespace {

std::string octal_mode(mode_t mode) {
    char text[8];
    std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
    return text;
}

// Who owns `path` and who may write it; `sticky_is_enough` for the directories above, whose
// entries others may not rename when the sticky bit is set.
std::optional<std::string> unsafe(const std::filesystem::path& path, const struct stat& status,
                                  uid_t daemon_uid, bool sticky_is_enough) {
    if (status.st_uid != 0 && status.st_uid != daemon_uid) {
        return path.string() + " is owned by uid " + std::to_string(status.st_uid) +
               ", neither root nor the daemon's user (uid " + std::to_string(daemon_uid) + ")";
    }
    const bool others_write = (status.st_mode & (S_IWGRP | S_IWOTH)) != 0;
    if (others_write && !(sticky_is_enough && (status.st_mode & S_ISVTX) != 0)) {
        return path.string() + " is writable by group or others (mode " +
               octal_mode(status.st_mode) + ")";
    }
    return std::nullopt;
}

std::optional<std::string> stat_of(const std::filesystem::path& path, struct stat& status) {
    if (::stat(path.c_str(), &status) != 0) {
        return path.string() + ": " + std::strerror(errno);
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> untrusted_directory(const std::filesystem::path& directory,
                                               uid_t daemon_uid) {
    std::error_code error;
    const auto real = std::filesystem::canonical(directory, error);
    if (error) {
        return directory.string() + ": " + error.message();
    }
    bool itself = true;
    for (auto path = real;; path = path.parent_path()) {
        struct stat status {};
        if (auto failed = stat_of(path, status)) {
            return failed;
        }
        if (!S_ISDIR(status.st_mode)) {
            return path.string() + " is not a directory";
        }
        if (auto reason = unsafe(path, status, daemon_uid, !itself)) {
            return reason;
        }
        itself = false;
        if (path == path.root_path()) {
            return std::nullopt;
        }
    }
}

std::optional<std::string> untrusted_module(const std::filesystem::path& module, uid_t daemon_uid) {
    std::error_code error;
    const auto real = std::filesystem::canonical(module, error);
    if (error) {
        return module.string() + ": " + error.message();
    }
    struct stat status {};
    if (auto failed = stat_of(real, status)) {
        return failed;
    }
    if (!S_ISREG(status.st_mode)) {
        return real.string() + " is not a regular file";
    }
    if (auto reason = unsafe(real, status, daemon_uid, false)) {
        return reason;
    }
    // A symlink may lead out of the drivers directory: where it leads must be as safe.
    return untrusted_directory(real.parent_path(), daemon_uid);
}

}  // namespace vibscore::drivers
