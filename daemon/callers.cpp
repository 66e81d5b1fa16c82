#include "daemon/callers.hpp"

#include <grp.h>
#include <pwd.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

bool user_in_group(uid_t uid, const char* group) {
    if (uid == 0) {
        return true;
    }
    std::vector<char> buffer(16384);
    struct group entry {};
    struct group* found_group = nullptr;
    if (getgrnam_r(group, &entry, buffer.data(), buffer.size(), &found_group) != 0 ||
        found_group == nullptr) {
        return false;  // no such group: only root is privileged
    }
    const gid_t wanted = found_group->gr_gid;
    std::vector<char> user_buffer(16384);
    struct passwd user {};
    struct passwd* found_user = nullptr;
    if (getpwuid_r(uid, &user, user_buffer.data(), user_buffer.size(), &found_user) != 0 ||
        found_user == nullptr) {
        return false;
    }
    int count = 64;
    std::vector<gid_t> groups(static_cast<std::size_t>(count));
    while (getgrouplist(found_user->pw_name, found_user->pw_gid, groups.data(), &count) < 0) {
        groups.resize(static_cast<std::size_t>(count));
    }
    groups.resize(static_cast<std::size_t>(count));
    return std::find(groups.begin(), groups.end(), wanted) != groups.end();
}

CallerDirectory::CallerDirectory(UidOfSender uid_of_sender)
    : uid_of_sender_(std::move(uid_of_sender)) {}

const Caller& CallerDirectory::identify(const sdbus::Message& message) {
    const std::string sender = dbus::sender_of(message);
    const auto found = callers_.find(sender);
    if (found != callers_.end()) {
        return found->second;
    }
    Caller caller;
    caller.sender = sender;
    caller.uid = uid_of_sender_ ? uid_of_sender_(sender) : message.getCredsUid();
    caller.privileged = user_in_group(caller.uid, "vibscore");
    return callers_.emplace(sender, std::move(caller)).first->second;
}

void CallerDirectory::forget(const std::string& sender) {
    callers_.erase(sender);
}

}  // namespace vibscore::daemon
