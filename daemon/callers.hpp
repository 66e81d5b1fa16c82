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
// cached per connection; and a token bucket of requests per user (twenty connections of one uid
// are one caller; root is not limited). The bus service no longer admits through this bucket:
// it admits by work, per connection and per user (admission.hpp), with the same request rate
// from the running configuration; admit() and set_rate() remain for reload_config and their
// tests, and could go with them.
class CallerDirectory {
  public:
    // Where a sender's user id comes from: the bus driver in the daemon (BusCredentials);
    // without one, sd-bus's sender credentials.
    using UidOfSender = std::function<uid_t(const std::string& sender)>;

    CallerDirectory(double requests_per_second, double burst, UidOfSender uid_of_sender = {});

    const Caller& identify(const sdbus::Message& message);
    // True if `uid` may make another request now; spends one token. A request needs a whole
    // token: half of one is not enough.
    bool admit(uid_t uid, std::uint64_t now_us);
    // The connection left the bus. Its user's bucket stays: leaving and coming back must not
    // refill it.
    void forget(const std::string& sender);
    void set_rate(double requests_per_second, double burst);
    double requests_per_second() const { return rate_; }

  private:
    struct Bucket {
        double tokens = 0.0;
        std::uint64_t updated_us = 0;
    };
    UidOfSender uid_of_sender_;
    std::unordered_map<std::string, Caller> callers_;
    std::unordered_map<uid_t, Bucket> buckets_;
    double rate_;
    double burst_;
};

// Is `uid` root or a member (primary or supplementary) of `group` in the user database?
bool user_in_group(uid_t uid, const char* group);

}  // namespace vibscore::daemon
