#pragma once

#include <string>
#include <string_view>

#include "daemon/callers.hpp"
#include "daemon/usage.hpp"

// Who may do what: polkit decides, as for every system service (timedated, NetworkManager).
// The actions and their defaults are in polkit/org.vibscore.policy; docs/daemon.md explains them.
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
enum class PolkitAnswer { authorized, not_authorized, unavailable };

// The seam to polkit: its CheckAuthorization for a caller on the bus, never interactive.
class PolkitAuthority {
  public:
    virtual ~PolkitAuthority() = default;
    // `unavailable` when polkit is not on the bus (not installed); throws std::runtime_error
    // when polkit is there but fails to answer.
    virtual PolkitAnswer check(const std::string& sender, std::string_view action_id) = 0;
};

// Decides for each call: root always may; otherwise polkit's answer about the caller's bus
// connection; where polkit is not on the bus, the rule before polkit (root or group vibscore,
// Caller::privileged). A polkit that fails refuses.
class Authorizer {
  public:
    explicit Authorizer(PolkitAuthority& polkit) : polkit_(polkit) {}

    bool allowed(const Caller& caller, Action action) const;
    // Throws RequestError (permission_denied) naming `what` the caller tried and the action.
    void require(const Caller& caller, Action action, std::string_view what) const;

  private:
    PolkitAuthority& polkit_;
};

}  // namespace vibscore::daemon
