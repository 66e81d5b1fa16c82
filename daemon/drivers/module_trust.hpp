#pragma once

#include <sys/stat.h>
#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "common/unique_fd.hpp"

// Whether vibscored may load code from a driver module: the module runs inside the daemon, with
// its privileges and its device access, so nobody but root and the daemon's own user may be able
// to put code there. The rules are sudo's and ssh's for their plugins and keys.
//
// Trust is given to what was opened, not to a name: the drivers directory is opened one
// component at a time with O_NOFOLLOW from /, each module is opened once below it with
// O_NOFOLLOW, owner and mode are checked on the open descriptors (fstat), and the daemon later
// loads that descriptor (/proc/self/fd/N). Renaming another file into place after the check
// changes nothing that is loaded. (openat2's RESOLVE_BENEATH would refuse the same paths, but
// not check the mode of each directory on the way, so the walk is done by hand everywhere.)
namespace vibscore::drivers {

// A file or directory opened and found trustworthy.
struct TrustedFile {
    std::filesystem::path path;  // as the daemon names it: DIR/NAME.so, not what a link names
    // Shared: the catalog, the trial and the loaded module keep the same descriptor open.
    std::shared_ptr<const UniqueFd> fd;
    struct stat status {};
};

// A TrustedFile, or why there is none.
struct TrustOutcome {
    std::optional<TrustedFile> file;
    std::string refusal;  // "" when `file` is set
};

// Opens the drivers directory `directory`: what it resolves to (links above it are resolved
// first, as the administrator configured them) is then opened from / one component at a time
// with O_NOFOLLOW. Every directory on the way must be owned by root or `daemon_uid`; the drivers
// directory must not be writable by group or others, one above it only if sticky (as /tmp is:
// nobody else may rename what is in it). A component swapped for a link while this runs is
// refused.
TrustOutcome open_trusted_directory(const std::filesystem::path& directory, uid_t daemon_uid);

// Opens module `name` (a file name) of the drivers directory open at `directory_fd` (named
// `directory` in messages). The file must be a regular file owned by root or `daemon_uid` that
// group and others may not write. A symlink is followed only when its target is a relative path
// below the drivers directory with no "..", whose directories pass the same checks and contain
// no link ("trace.so -> trace.so.2", "trace.so -> v2/trace.so"); any other link, one that leaves
// the directory or leads to another link, is refused naming the link and its target.
TrustOutcome open_trusted_module(int directory_fd, const std::filesystem::path& directory,
                                 const std::string& name, uid_t daemon_uid);

// open_trusted_directory(module's directory) then open_trusted_module(module's name).
TrustOutcome open_trusted_module(const std::filesystem::path& module, uid_t daemon_uid);

// Why `file` must no longer be loaded, or nullopt when it still may: its descriptor is still the
// file that was checked (device, inode, size and modification time), and still passes the owner
// and mode checks (nobody else was let write it since).
std::optional<std::string> changed_since_checked(const TrustedFile& file, uid_t daemon_uid);

// The name under which the dynamic loader opens `fd` itself: "/proc/self/fd/N".
std::string descriptor_path(const UniqueFd& fd);

// The refusals of the two opens above, for callers that only ask (nullopt: trusted).
std::optional<std::string> untrusted_directory(const std::filesystem::path& directory,
                                               uid_t daemon_uid);
std::optional<std::string> untrusted_module(const std::filesystem::path& module, uid_t daemon_uid);

}  // namespace vibscore::drivers
