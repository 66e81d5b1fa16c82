#pragma once

#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>

namespace sdbus {
class Message;
}

namespace vibscore::daemon {

struct Caller {
    std::string sender;  // unique bus name, ":1.42"
    uid_t uid = 0;
    bool privileged = false;  // root, or a member of group "vibscore"
};

// Who is calling, from the bus's credentials for the sender (not from anything the caller says),
// cached per connection. What a caller may spend is admission's (admission.hpp: per connection
// and per user, by work).
class CallerDirectory {
  public:
    // Where a sender's user id comes from: the bus driver in the daemon (BusCredentials);
    // without one, sd-bus's sender credentials.
    using UidOfSender = std::function<uid_t(const std::string& sender)>;

    explicit CallerDirectory(UidOfSender uid_of_sender = {});

    const Caller& identify(const sdbus::Message& message);
    // The connection left the bus: a new one of that name is asked again.
    void forget(const std::string& sender);

  private:
    UidOfSender uid_of_sender_;
    std::unordered_map<std::string, Caller> callers_;
};

// Is `uid` root or a member (primary or supplementary) of `group` in the user database?
bool user_in_group(uid_t uid, const char* group);

}  // namespace vibscore::daemon
