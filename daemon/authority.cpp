#include "daemon/authority.hpp"

#include <stdexcept>

#include "daemon/log.hpp"
#include "daemon/request_error.hpp"

namespace vibscore::daemon {

namespace {

enum class Verdict { allowed, refused_by_polkit, refused_by_group_rule, polkit_failed };

Verdict decide(PolkitAuthority& polkit, const Caller& caller, Action action, std::string* failure) {
    if (caller.uid == 0) {
        return Verdict::allowed;
    }
    try {
        switch (polkit.check(caller.sender, action_id(action))) {
            case PolkitAnswer::authorized:
                return Verdict::allowed;
            case PolkitAnswer::not_authorized:
                return Verdict::refused_by_polkit;
            case PolkitAnswer::unavailable:
                return caller.privileged ? Verdict::allowed : Verdict::refused_by_group_rule;
        }
    } catch (const std::runtime_error& error) {
        *failure = error.what();
        log::error("polkit could not check " + std::string(action_id(action)) + " for uid " +
                   std::to_string(caller.uid) + ": " + error.what());
    }
    return Verdict::polkit_failed;
}

}  // namespace

std::string_view action_id(Action action) {
    switch (action) {
        case Action::compose:
            return "org.vibscore.compose";
        case Action::manage:
            return "org.vibscore.manage";
        case Action::urgent_usage:
            return "org.vibscore.urgent-usage";
    }
    return "org.vibscore.manage";
}

bool needs_urgent_usage(Usage usage) {
    return usage == Usage::ringtone || usage == Usage::alarm;
}

bool Authorizer::allowed(const Caller& caller, Action action) const {
    std::string failure;
    return decide(polkit_, caller, action, &failure) == Verdict::allowed;
}

void Authorizer::require(const Caller& caller, Action action, std::string_view what) const {
    std::string failure;
    const auto verdict = decide(polkit_, caller, action, &failure);
    const std::string needs = std::string(what) + " needs " + std::string(action_id(action));
    const std::string uid = "uid " + std::to_string(caller.uid);
    switch (verdict) {
        case Verdict::allowed:
            return;
        case Verdict::refused_by_polkit:
            throw RequestError(RequestError::Code::permission_denied,
                               needs + ", which polkit does not grant to " + uid);
        case Verdict::refused_by_group_rule:
            throw RequestError(RequestError::Code::permission_denied,
                               needs + "; polkit is not running, so only root and group " +
                                   "vibscore have it, and " + uid + " is neither");
        case Verdict::polkit_failed:
            throw RequestError(
                RequestError::Code::permission_denied,
                needs + ", and polkit could not check it for " + uid + ": " + failure);
    }
}

}  // namespace vibscore::daemon
