#include "daemon/authority.hpp"

#include "common/log.hpp"
#include "daemon/request_error.hpp"

namespace vibscore::daemon {

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

void Decision::require(std::string_view what) const {
    const std::string needs = std::string(what) + " needs " + std::string(action_id(action_));
    const std::string uid = "uid " + std::to_string(uid_);
    switch (verdict_) {
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
                needs + ", and polkit could not check it for " + uid + ": " + failure_);
        case Verdict::too_many_pending:
            throw RequestError(RequestError::Code::limit_exceeded,
                               needs + ", and " + uid + " already waits for polkit's answer to " +
                                   failure_ + " questions: try again when they are answered");
    }
}

std::optional<Decision> Authorizer::known(const Caller& caller, Action action) const {
    if (caller.uid == 0) {
        return Decision(Decision::Verdict::allowed, action, caller.uid);
    }
    const auto kept = kept_.find({caller.sender, action});
    if (kept != kept_.end()) {
        return Decision(kept->second, action, caller.uid);
    }
    return std::nullopt;
}

std::size_t Authorizer::pending_for(uid_t uid) const {
    std::size_t count = 0;
    for (const auto& [key, pending] : pending_) {
        count += pending.uid == uid ? 1 : 0;
    }
    return count;
}

void Authorizer::decide(const Caller& caller, Action action, Decided decided) {
    if (auto decision = known(caller, action)) {
        decided(*decision);
        return;
    }
    Key key{caller.sender, action};
    const auto open = pending_.find(key);
    if (open != pending_.end()) {
        open->second.waiting.push_back(std::move(decided));
        return;
    }
    if (pending_for(caller.uid) >= max_pending_per_user_) {
        decided(Decision(Decision::Verdict::too_many_pending, action, caller.uid,
                         std::to_string(max_pending_per_user_)));
        return;
    }
    pending_[key] = Pending{caller.uid, {std::move(decided)}};
    // The answer may come at once (polkit not on the bus): answered() then runs inside check().
    polkit_.check(caller.sender, action_id(action),
                  [this, key, caller](PolkitAnswer answer, const std::string& failure) {
                      answered(key, caller, answer, failure);
                  });
}

void Authorizer::answered(const Key& key, const Caller& caller, PolkitAnswer answer,
                          const std::string& failure) {
    const auto open = pending_.find(key);
    if (open == pending_.end()) {
        return;
    }
    const bool keep = !open->second.forgotten;
    auto waiting = std::move(open->second.waiting);
    pending_.erase(open);

    const auto action = key.second;
    auto verdict = Decision::Verdict::polkit_failed;
    switch (answer) {
        case PolkitAnswer::authorized:
            verdict = Decision::Verdict::allowed;
            break;
        case PolkitAnswer::not_authorized:
            verdict = Decision::Verdict::refused_by_polkit;
            break;
        case PolkitAnswer::unavailable:
            verdict = caller.privileged ? Decision::Verdict::allowed
                                        : Decision::Verdict::refused_by_group_rule;
            break;
        case PolkitAnswer::failed:
            log::error("polkit could not check " + std::string(action_id(action)) + " for uid " +
                       std::to_string(caller.uid) + ": " + failure);
            break;
    }
    // Only polkit's definite answers are kept: polkit may start later, or recover.
    if (keep && (answer == PolkitAnswer::authorized || answer == PolkitAnswer::not_authorized)) {
        kept_[key] = verdict;
    }
    const Decision decision(verdict, action, caller.uid, failure);
    for (auto& decided : waiting) {
        decided(decision);
    }
}

void Authorizer::forget(const std::string& sender) {
    for (auto kept = kept_.begin(); kept != kept_.end();) {
        kept = kept->first.first == sender ? kept_.erase(kept) : std::next(kept);
    }
    // An open question stays open until polkit answers it (its count still bounds what the
    // user asks at once); the answer then goes to nobody.
    for (auto& [key, pending] : pending_) {
        if (key.first == sender) {
            pending.waiting.clear();
            pending.forgotten = true;
        }
    }
}

}  // namespace vibscore::daemon
