#include "daemon/admission.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/ini_reader.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"

namespace vibscore::daemon {

namespace {

// Whether `tokens` of one resource cover `cost` of it (see TokenBucket).
bool resource_covers(double tokens, double burst, double cost) {
    return cost <= 0.0 || tokens >= std::min(cost, burst);
}

double refilled(double tokens, double rate, double burst, double elapsed_s) {
    return std::min(burst, tokens + elapsed_s * rate);
}

std::string mib(double bytes) {
    return number_text(bytes / (1024.0 * 1024.0)) + " MiB";
}

// What the budget a refused request met allows, in words.
std::string budget_text(const Budget& budget) {
    return number_text(budget.rate.requests) + " requests, " + mib(budget.rate.bytes) +
           " of documents and " + number_text(budget.rate.cpu_s) +
           " s of CPU a second (bursts of " + number_text(budget.burst.requests) + ", " +
           mib(budget.burst.bytes) + ", " + number_text(budget.burst.cpu_s) + " s)";
}

// "too many requests from uid 1000" or what else `bucket` lacks for `cost`.
std::string what_is_short(const TokenBucket& bucket, const Budget& budget, const Cost& cost,
                          uid_t uid) {
    const auto& tokens = bucket.tokens();
    const std::string who = " from uid " + std::to_string(uid);
    if (!resource_covers(tokens.requests, budget.burst.requests, cost.requests)) {
        return "too many requests" + who;
    }
    if (!resource_covers(tokens.bytes, budget.burst.bytes, cost.bytes)) {
        return "too many document bytes" + who;
    }
    return "too much CPU time spent on the work of uid " + std::to_string(uid);
}

double number_in(const std::string& key, const std::string& value, double low, double high) {
    const auto number = ini_number(value);
    if (!number || *number < low || *number > high) {
        throw std::invalid_argument(key + " = " + quoted_text(value) + " is not a number from " +
                                    number_text(low) + " to " + number_text(high));
    }
    return *number;
}

}  // namespace

Cost operator*(const Cost& cost, double factor) {
    return {cost.requests * factor, cost.bytes * factor, cost.cpu_s * factor};
}

TokenBucket::TokenBucket(const Budget& budget, std::uint64_t now_us)
    : tokens_(budget.burst), updated_us_(now_us) {}

void TokenBucket::refill(const Budget& budget, std::uint64_t now_us) {
    if (now_us <= updated_us_) {
        return;
    }
    const double elapsed_s = static_cast<double>(now_us - updated_us_) / 1e6;
    tokens_.requests =
        refilled(tokens_.requests, budget.rate.requests, budget.burst.requests, elapsed_s);
    tokens_.bytes = refilled(tokens_.bytes, budget.rate.bytes, budget.burst.bytes, elapsed_s);
    tokens_.cpu_s = refilled(tokens_.cpu_s, budget.rate.cpu_s, budget.burst.cpu_s, elapsed_s);
    updated_us_ = now_us;
}

bool TokenBucket::covers(const Budget& budget, const Cost& cost) const {
    return resource_covers(tokens_.requests, budget.burst.requests, cost.requests) &&
           resource_covers(tokens_.bytes, budget.burst.bytes, cost.bytes) &&
           resource_covers(tokens_.cpu_s, budget.burst.cpu_s, cost.cpu_s);
}

void TokenBucket::charge(const Cost& cost) {
    tokens_.requests -= cost.requests;
    tokens_.bytes -= cost.bytes;
    tokens_.cpu_s -= cost.cpu_s;
}

bool TokenBucket::at_least_half_full(const Budget& budget) const {
    return tokens_.requests >= budget.burst.requests / 2 &&
           tokens_.bytes >= budget.burst.bytes / 2 && tokens_.cpu_s >= budget.burst.cpu_s / 2;
}

Budget AdmissionBudgets::connection() const {
    return {user.rate * connection_share, user.burst * connection_share};
}

Budget AdmissionBudgets::shared() const {
    return {user.rate * (1.0 - reserve_share), user.burst * (1.0 - reserve_share)};
}

Budget AdmissionBudgets::reserve() const {
    return {user.rate * reserve_share, user.burst * reserve_share};
}

bool AdmissionBudgets::set(const std::string& key, const std::string& value) {
    // The byte bounds: at least one byte a second; at most 1 GiB, past any sense on a phone.
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    if (key == "document-bytes-per-second") {
        user.rate.bytes = number_in(key, value, 1.0, kGiB);
    } else if (key == "document-burst-bytes") {
        user.burst.bytes = number_in(key, value, 1.0, kGiB);
    } else if (key == "work-cpu-per-second") {
        // A fraction of one core; above 1 a user could take more than one core of the worker's.
        user.rate.cpu_s = number_in(key, value, 0.001, 1.0);
    } else if (key == "work-cpu-burst") {
        user.burst.cpu_s = number_in(key, value, 0.001, 60.0);
    } else if (key == "connection-share") {
        connection_share = number_in(key, value, 0.01, 1.0);
    } else {
        return false;
    }
    return true;
}

bool Admission::exempt(uid_t uid) {
    static const uid_t self = ::geteuid();
    return uid == 0 || uid == self;
}

Admission::UserBuckets& Admission::user(uid_t uid, std::uint64_t now_us) {
    auto [found, fresh] =
        users_.try_emplace(uid, UserBuckets{TokenBucket(budgets_.shared(), now_us),
                                            TokenBucket(budgets_.reserve(), now_us)});
    if (!fresh) {
        found->second.main.refill(budgets_.shared(), now_us);
        found->second.reserve.refill(budgets_.reserve(), now_us);
    }
    return found->second;
}

TokenBucket& Admission::connection(const std::string& name, std::uint64_t now_us) {
    const Budget budget = budgets_.connection();
    auto [found, fresh] = connections_.try_emplace(name, budget, now_us);
    if (!fresh) {
        found->second.refill(budget, now_us);
    }
    return found->second;
}

Admitted Admission::admit(uid_t uid, const std::string& name, const Cost& cost,
                          std::uint64_t now_us) {
    if (exempt(uid)) {
        return {true, ChargedTo::nothing, {}};
    }
    auto& own = connection(name, now_us);
    auto& users = user(uid, now_us);
    const auto refuse = [&](std::string why) {
        own.charge({std::min(1.0, std::max(0.0, own.tokens().requests)), 0.0, 0.0});
        return Admitted{false, ChargedTo::nothing, std::move(why)};
    };
    const Budget connection_budget = budgets_.connection();
    if (!own.covers(connection_budget, cost)) {
        return refuse(what_is_short(own, connection_budget, cost, uid) + ": connection " + name +
                      " has spent its share of its user's budget (" +
                      budget_text(connection_budget) + ", [limits] connection-share); " +
                      "refused before its work");
    }
    if (users.main.covers(budgets_.shared(), cost)) {
        own.charge(cost);
        users.main.charge(cost);
        return {true, ChargedTo::user, {}};
    }
    TokenBucket after = own;
    after.charge(cost);
    if (after.at_least_half_full(connection_budget) &&
        users.reserve.covers(budgets_.reserve(), cost)) {
        own = after;
        users.reserve.charge(cost);
        return {true, ChargedTo::reserve, {}};
    }
    return refuse(what_is_short(users.main, budgets_.shared(), cost, uid) +
                  ": its connections together have spent its budget (" +
                  budget_text(budgets_.user) +
                  "; [daemon] requests-per-second, request-burst; [limits] "
                  "document-bytes-per-second, document-burst-bytes, work-cpu-per-second, "
                  "work-cpu-burst); refused before its work");
}

void Admission::charge_after(uid_t uid, const std::string& name, ChargedTo charged_to,
                             const Cost& cost, std::uint64_t now_us) {
    if (charged_to == ChargedTo::nothing || exempt(uid)) {
        return;
    }
    // A connection that left meanwhile has no bucket to charge; its user still pays.
    if (connections_.contains(name)) {
        connection(name, now_us).charge(cost);
    }
    auto& users = user(uid, now_us);
    (charged_to == ChargedTo::user ? users.main : users.reserve).charge(cost);
}

void Admission::forget(const std::string& name) {
    connections_.erase(name);
}

Cost Admission::user_tokens(uid_t uid, std::uint64_t now_us) {
    return user(uid, now_us).main.tokens();
}

Cost Admission::connection_tokens(const std::string& name, std::uint64_t now_us) {
    return connection(name, now_us).tokens();
}

}  // namespace vibscore::daemon
