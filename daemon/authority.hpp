#pragma once

#include <sys/types.h>

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/usage.hpp"
#include "daemon/callers.hpp"

// Who may do what: polkit decides, as for every system service (timedated, NetworkManager).
// The actions and their defaults are in polkit/org.vibscore.policy; docs/daemon.md explains them.
// polkit is asked without waiting for it (as systemd's bus-polkit.c does): the bus thread goes on
// serving everyone else while one caller's question is open.
namespace vibscore::daemon {

enum class Action {
    compose,       // Compose, Delete
    manage,        // SwitchDriver, setting Intensity, stopping another user's playback
    urgent_usage,  // Play with a usage that preempts the others (ringtone, alarm)
};

// "org.vibscore.compose", "org.vibscore.manage", "org.vibscore.urgent-usage".
std::string_view action_id(Action action);

// Usages that take the actuator from any other playback need org.vibscore.urgent-usage.
bool needs_urgent_usage(Usage usage);

// polkit's answer about one bus connection and one action.
enum class PolkitAnswer { authorized, not_authorized, unavailable, failed };

// The seam to polkit: its CheckAuthorization for a caller on the bus, never interactive and
// never waited for. `answered` runs later on the thread that serves the bus (or at once, when the
// answer is known without asking); `failure` says why when the answer is `failed`.
class PolkitAuthority {
  public:
    using Answered = std::function<void(PolkitAnswer answer, const std::string& failure)>;
    virtual ~PolkitAuthority() = default;
    virtual void check(const std::string& sender, std::string_view action_id,
                       Answered answered) = 0;
};

// What was decided about one caller and one action.
class Decision {
  public:
    enum class Verdict {
        allowed,
        refused_by_polkit,
        refused_by_group_rule,  // polkit is not on the bus: only root and group vibscore may
        polkit_failed,
        too_many_pending,  // the caller's user has too many questions open already
    };

    Decision(Verdict verdict, Action action, uid_t uid, std::string failure = {})
        : verdict_(verdict), action_(action), uid_(uid), failure_(std::move(failure)) {}

    Verdict verdict() const { return verdict_; }
    bool allowed() const { return verdict_ == Verdict::allowed; }
    // Throws RequestError naming `what` the caller tried, the action and why it was refused
    // (permission_denied; limit_exceeded for too_many_pending); returns when allowed.
    void require(std::string_view what) const;

  private:
    Verdict verdict_;
    Action action_;
    uid_t uid_;
    std::string failure_;
};

// Decides for each call: root always may; otherwise polkit's answer about the caller's bus
// connection, kept for that connection's lifetime as polkit's own clients keep it (forget() when
// it leaves the bus); where polkit is not on the bus, the rule before polkit (root or group
// vibscore, Caller::privileged). A polkit that fails refuses, and is asked again next time.
// Questions about the same connection and action that are open at once share polkit's one
// answer; a user may have at most `max_pending_per_user` different ones open.
class Authorizer {
  public:
    using Decided = std::function<void(const Decision&)>;
    static constexpr std::size_t kMaxPendingPerUser = 16;

    explicit Authorizer(PolkitAuthority& polkit,
                        std::size_t max_pending_per_user = kMaxPendingPerUser)
        : polkit_(polkit), max_pending_per_user_(max_pending_per_user) {}

    // Calls `decided` with the decision: at once when it is known without asking polkit (root,
    // a verdict kept for this connection, too many open questions), otherwise when polkit
    // answers.
    void decide(const Caller& caller, Action action, Decided decided);
    // The decision when it is known without asking polkit; nullopt when polkit must be asked.
    std::optional<Decision> known(const Caller& caller, Action action) const;
    // The connection left the bus: its verdicts go (a new connection with its name, which the
    // bus never reuses, would be asked about afresh anyway).
    void forget(const std::string& sender);

    // Open questions (for tests and the log).
    std::size_t pending() const { return pending_.size(); }

  private:
    using Key = std::pair<std::string, Action>;  // sender, action
    struct Pending {
        uid_t uid = 0;
        std::vector<Decided> waiting;
        bool forgotten = false;  // the caller left the bus: nobody waits, nothing is kept
    };
    void answered(const Key& key, const Caller& caller, PolkitAnswer answer,
                  const std::string& failure);
    std::size_t pending_for(uid_t uid) const;

    PolkitAuthority& polkit_;
    std::size_t max_pending_per_user_;
    std::map<Key, Decision::Verdict> kept_;  // polkit's definite answers, per connection
    std::map<Key, Pending> pending_;
};

}  // namespace vibscore::daemon
