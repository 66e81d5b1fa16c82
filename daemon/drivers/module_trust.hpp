#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>

// Whether vibscored may load code from a driver module: the module runs inside the daemon, with
// its privileges and its device access, so nobody but root and the daemon's own user may be able
// to put code there. The rules are sudo's and ssh's for their plugins and keys.
namespace vibscore::drivers {

// Why the drivers directory must not be used, or nullopt when it may: it and every directory
// above it must be owned by root or `daemon_uid`; it must not be writable by group or others,
// and a directory above it only if sticky (as /tmp is: nobody else may rename what is in it).
std::optional<std::string> untrusted_directory(const std::filesystem::path& directory,
                                               uid_t daemon_uid);

// Why a module file must not be loaded, or nullopt when it may: it (what a symlink names) must
// be a regular file owned by root or `daemon_uid` and not writable by group or others, in a
// directory untrusted_directory() accepts.
std::optional<std::string> untrusted_module(const std::filesystem::path& module, uid_t daemon_uid);

}  // namespace vibscore::drivers
