#pragma once

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>

// Admission by work (issue 33, item 1): what a request costs the daemon (one request, the bytes
// of the documents it carries, the CPU time its parsing and binding took) is charged to token
// buckets of its connection and of its user, before any of its work is done; the CPU time, known
// only afterwards, is charged when the work has run. A caller whose buckets cannot cover a
// request is refused (LimitExceeded) before anything is parsed. docs/daemon.md, Limits.
namespace vibscore::daemon {

// An amount of each resource: a request's cost, a bucket's content, a rate (per second) or a
// burst (the most a bucket holds).
struct Cost {
    double requests = 0.0;
    double bytes = 0.0;  // of documents carried (an inline score, clefs sent along)
    double cpu_s = 0.0;  // of the daemon's CPU spent on the request's work
    bool operator==(const Cost&) const = default;
};

Cost operator*(const Cost& cost, double factor);

struct Budget {
    Cost rate;   // per second
    Cost burst;  // the most a bucket holds; a fresh bucket is full
    bool operator==(const Budget&) const = default;
};

// One token bucket per resource. Tokens come back at `rate` up to `burst`. A cost is covered when
// each resource it asks for (cost above 0) has at least that much, or a whole burst when the cost
// is larger than the burst (so one document larger than the burst passes from a full bucket,
// leaving the bucket in debt). Charging may leave a resource below 0 (the CPU time measured
// afterwards, a large document): a debt that refuses what needs that resource until it is repaid.
class TokenBucket {
  public:
    TokenBucket(const Budget& budget, std::uint64_t now_us);
    // Tokens come back for the time since the last refill, up to the burst.
    void refill(const Budget& budget, std::uint64_t now_us);
    bool covers(const Budget& budget, const Cost& cost) const;
    void charge(const Cost& cost);
    // Every resource at least half its burst: the connection is not spending faster than its
    // budget comes back.
    bool at_least_half_full(const Budget& budget) const;
    const Cost& tokens() const { return tokens_; }

  private:
    Cost tokens_;
    std::uint64_t updated_us_;
};

// The budgets: a user's, and the fractions of it one connection and the quiet reserve get.
struct AdmissionBudgets {
    // [daemon] requests-per-second / request-burst; [limits] document-bytes-per-second,
    // document-burst-bytes, work-cpu-per-second, work-cpu-burst.
    Budget user{{50.0, 2.0 * 1024 * 1024, 0.25}, {100.0, 4.0 * 1024 * 1024, 0.5}};
    // [limits] connection-share: each connection's own buckets, as a fraction of its user's.
    double connection_share = 0.5;
    // The part of the user's budget held back for its quiet connections: one that is not
    // spending faster than its own budget comes back (its buckets at least half full after the
    // request) may take from it once the rest of its user's budget is spent, so a user's other
    // app keeps its calls while one app floods. A quarter of the user's budget; the rest is
    // `shared()`, for any of the user's connections.
    double reserve_share = 0.25;

    Budget connection() const;
    Budget shared() const;
    Budget reserve() const;
    bool operator==(const AdmissionBudgets&) const = default;

    // One [limits] key of the budgets: true if `key` is one (and its value was taken), false
    // for any other key. Throws std::invalid_argument naming the key and the value for a value
    // that is not a number in range.
    bool set(const std::string& key, const std::string& value);
};

// Where an admitted request's cost was charged, to charge its measured CPU time to the same.
enum class ChargedTo { nothing, user, reserve };

struct Admitted {
    bool admitted = false;
    ChargedTo charged_to = ChargedTo::nothing;
    std::string refusal;  // why not, for LimitExceeded: names the budget and its key
};

// The buckets of every user and connection that called. Single-threaded: the bus thread's.
class Admission {
  public:
    explicit Admission(AdmissionBudgets budgets = {}) : budgets_(budgets) {}

    // Root and the daemon's own user are never charged: they keep their head-room.
    static bool exempt(uid_t uid);

    // Charges `cost` to `connection`'s buckets and to its user's (or, for a quiet connection
    // whose user's buckets are spent, to the user's reserve), or refuses. A refused request
    // still spends one request token of its connection (never below 0): a connection that keeps
    // calling while refused stays refused and is not quiet.
    Admitted admit(uid_t uid, const std::string& connection, const Cost& cost,
                   std::uint64_t now_us);
    // What the request's work cost once it ran (its CPU time), charged where it was admitted.
    void charge_after(uid_t uid, const std::string& connection, ChargedTo charged_to,
                      const Cost& cost, std::uint64_t now_us);
    // The connection left the bus: its buckets go. Its user's stay (leaving and coming back does
    // not refill them).
    void forget(const std::string& connection);
    void set_budgets(const AdmissionBudgets& budgets) { budgets_ = budgets; }
    const AdmissionBudgets& budgets() const { return budgets_; }
    std::size_t connections() const { return connections_.size(); }

    // For tests: a bucket's tokens (refilled to `now_us`).
    Cost user_tokens(uid_t uid, std::uint64_t now_us);
    Cost connection_tokens(const std::string& connection, std::uint64_t now_us);

  private:
    struct UserBuckets {
        TokenBucket main;
        TokenBucket reserve;
    };
    UserBuckets& user(uid_t uid, std::uint64_t now_us);
    TokenBucket& connection(const std::string& connection, std::uint64_t now_us);

    AdmissionBudgets budgets_;
    std::unordered_map<uid_t, UserBuckets> users_;
    std::unordered_map<std::string, TokenBucket> connections_;
};

}  // namespace vibscore::daemon
