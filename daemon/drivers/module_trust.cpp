#include "daemon/drivers/module_trust.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <vector>

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

TrustOutcome refused(std::string why) {
    return {std::nullopt, std::move(why)};
}

std::string failure(const std::filesystem::path& path, int error) {
    return path.string() + ": " + std::strerror(error);
}

constexpr std::string_view kALink = " is a symbolic link";

// Opens `name` below `at` with O_NOFOLLOW and checks it; a directory with O_PATH, since only
// its last one is listed and the daemon's user may search directories it cannot read.
TrustOutcome open_checked(int at, const std::string& name, const std::filesystem::path& shown,
                          bool directory, bool sticky_is_enough, uid_t daemon_uid) {
    const int flags = O_CLOEXEC | O_NOFOLLOW |
                      (directory ? O_DIRECTORY | O_PATH : O_RDONLY | O_NONBLOCK | O_NOCTTY);
    auto fd = std::make_shared<UniqueFd>(::openat(at, name.c_str(), flags));
    if (fd->get() < 0) {
        const int error = errno;
        struct stat entry {};
        if ((error == ELOOP || error == ENOTDIR) &&
            ::fstatat(at, name.c_str(), &entry, AT_SYMLINK_NOFOLLOW) == 0 &&
            S_ISLNK(entry.st_mode)) {
            return refused(shown.string() + std::string(kALink));
        }
        return refused(failure(shown, error));
    }
    TrustedFile file{shown, fd, {}};
    if (::fstat(fd->get(), &file.status) != 0) {
        return refused(failure(shown, errno));
    }
    if (S_ISLNK(file.status.st_mode)) {  // O_PATH | O_NOFOLLOW opens the link itself
        return refused(shown.string() + std::string(kALink));
    }
    if (directory ? !S_ISDIR(file.status.st_mode) : !S_ISREG(file.status.st_mode)) {
        return refused(shown.string() +
                       (directory ? " is not a directory" : " is not a regular file"));
    }
    if (auto reason = unsafe(shown, file.status, daemon_uid, sticky_is_enough)) {
        return refused(*reason);
    }
    return {std::move(file), ""};
}

// Reopens the drivers directory read-only (O_PATH cannot be listed) through its own descriptor,
// so it is still the directory that was checked.
TrustOutcome readable(TrustedFile directory) {
    auto fd = std::make_shared<UniqueFd>(
        ::openat(directory.fd->get(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW));
    if (fd->get() < 0) {
        return refused(failure(directory.path, errno));
    }
    struct stat status {};
    if (::fstat(fd->get(), &status) != 0 || status.st_dev != directory.status.st_dev ||
        status.st_ino != directory.status.st_ino) {
        return refused(directory.path.string() + " changed while it was checked");
    }
    directory.fd = std::move(fd);
    return {std::move(directory), ""};
}

// The components of a relative link target, or nullopt when it leaves where it starts ("..",
// an absolute path) or is empty.
std::optional<std::vector<std::string>> components_beneath(const std::string& target) {
    if (target.empty() || target.front() == '/') {
        return std::nullopt;
    }
    std::vector<std::string> parts;
    for (const auto& part : std::filesystem::path(target)) {
        const std::string text = part.string();
        if (text == "..") {
            return std::nullopt;
        }
        if (!text.empty() && text != ".") {
            parts.push_back(text);
        }
    }
    if (parts.empty()) {
        return std::nullopt;
    }
    return parts;
}

}  // namespace

TrustOutcome open_trusted_directory(const std::filesystem::path& directory, uid_t daemon_uid) {
    std::error_code error;
    const auto real = std::filesystem::canonical(directory, error);
    if (error) {
        return refused(directory.string() + ": " + error.message());
    }
    const auto relative = real.relative_path();
    const std::vector<std::filesystem::path> parts(relative.begin(), relative.end());
    auto opened = open_checked(AT_FDCWD, "/", "/", true, !parts.empty(), daemon_uid);
    std::filesystem::path shown = "/";
    for (std::size_t i = 0; i < parts.size() && opened.file; ++i) {
        shown /= parts[i];
        const bool last = i + 1 == parts.size();
        opened =
            open_checked(opened.file->fd->get(), parts[i].string(), shown, true, !last, daemon_uid);
    }
    if (!opened.file) {
        return opened;
    }
    opened.file->path = directory;
    return readable(std::move(*opened.file));
}

TrustOutcome open_trusted_module(int directory_fd, const std::filesystem::path& directory,
                                 const std::string& name, uid_t daemon_uid) {
    const auto path = directory / name;
    struct stat entry {};
    if (::fstatat(directory_fd, name.c_str(), &entry, AT_SYMLINK_NOFOLLOW) != 0) {
        return refused(failure(path, errno));
    }
    if (!S_ISLNK(entry.st_mode)) {
        return open_checked(directory_fd, name, path, false, false, daemon_uid);
    }
    std::vector<char> target(static_cast<std::size_t>(entry.st_size > 0 ? entry.st_size : 255) + 2);
    const ssize_t length = ::readlinkat(directory_fd, name.c_str(), target.data(), target.size());
    if (length < 0 || static_cast<std::size_t>(length) >= target.size()) {
        return refused(failure(path, length < 0 ? errno : ENAMETOOLONG));
    }
    const std::string link =
        path.string() + " -> " + std::string(target.data(), static_cast<std::size_t>(length));
    const auto parts =
        components_beneath(std::string(target.data(), static_cast<std::size_t>(length)));
    if (!parts) {
        return refused(link + " leads out of the drivers directory " + directory.string() +
                       " (a link there may only name a file below it)");
    }
    // Below the drivers directory nothing may be writable by others, sticky or not.
    TrustOutcome opened{TrustedFile{directory, nullptr, {}}, ""};
    auto at = directory_fd;
    std::filesystem::path shown = directory;
    for (std::size_t i = 0; i < parts->size(); ++i) {
        shown /= (*parts)[i];
        const bool last = i + 1 == parts->size();
        auto next = open_checked(at, (*parts)[i], shown, !last, false, daemon_uid);
        if (!next.file) {
            const bool a_link = next.refusal.ends_with(kALink);
            return refused(link + ": " +
                           (a_link ? next.refusal + " too (one link is followed, and only to a "
                                                    "file)"
                                   : next.refusal));
        }
        opened = std::move(next);
        at = opened.file->fd->get();
    }
    opened.file->path = path;  // the name the daemon lists, with what it named checked
    return opened;
}

TrustOutcome open_trusted_module(const std::filesystem::path& module, uid_t daemon_uid) {
    const auto parent = module.has_parent_path() ? module.parent_path() : ".";
    auto directory = open_trusted_directory(parent, daemon_uid);
    if (!directory.file) {
        return directory;
    }
    return open_trusted_module(directory.file->fd->get(), parent, module.filename().string(),
                               daemon_uid);
}

std::optional<std::string> changed_since_checked(const TrustedFile& file, uid_t daemon_uid) {
    struct stat now {};
    if (!file.fd || ::fstat(file.fd->get(), &now) != 0) {
        return file.path.string() + ": its descriptor is gone";
    }
    const auto& then = file.status;
    if (now.st_dev != then.st_dev || now.st_ino != then.st_ino || now.st_size != then.st_size ||
        now.st_mtim.tv_sec != then.st_mtim.tv_sec || now.st_mtim.tv_nsec != then.st_mtim.tv_nsec) {
        return file.path.string() +
               " changed since it was checked and tried (a reload tries it again)";
    }
    return unsafe(file.path, now, daemon_uid, false);
}

std::string descriptor_path(const UniqueFd& fd) {
    return "/proc/self/fd/" + std::to_string(fd.get());
}

std::optional<std::string> untrusted_directory(const std::filesystem::path& directory,
                                               uid_t daemon_uid) {
    auto opened = open_trusted_directory(directory, daemon_uid);
    return opened.file ? std::nullopt : std::optional(opened.refusal);
}

std::optional<std::string> untrusted_module(const std::filesystem::path& module, uid_t daemon_uid) {
    auto opened = open_trusted_module(module, daemon_uid);
    return opened.file ? std::nullopt : std::optional(opened.refusal);
}

}  // namespace vibscore::drivers
