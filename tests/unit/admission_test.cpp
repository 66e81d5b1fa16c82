// Admission by work (issue 33, item 1): token buckets per connection and per user, charged with
// what a request costs, each limit at its edge (the last request admitted, the first refused,
// the refill).
#include "daemon/admission.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vibscore::daemon {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr std::uint64_t kSecond = 1'000'000;
constexpr uid_t kUser = 1000;
constexpr double kMiB = 1024.0 * 1024.0;

// Round numbers: a user gets 8 requests a second (bursts of 8), 4 MiB of documents a second
// (bursts of 4 MiB), 1 s of CPU a second (bursts of 1 s); a connection half of that; the
// reserve a quarter, the shared part three quarters.
AdmissionBudgets budgets() {
    AdmissionBudgets budgets;
    budgets.user = {{8.0, 4 * kMiB, 1.0}, {8.0, 4 * kMiB, 1.0}};
    budgets.connection_share = 0.5;
    budgets.reserve_share = 0.25;
    return budgets;
}

const Cost kRequest{1.0, 0.0, 0.0};

Cost document(double bytes) {
    return {1.0, bytes, 1e-9};
}

int admitted(Admission& admission, const std::string& connection, int tries, std::uint64_t at,
             const Cost& cost = kRequest, uid_t uid = kUser) {
    int count = 0;
    for (int i = 0; i < tries; ++i) {
        count += admission.admit(uid, connection, cost, at).admitted ? 1 : 0;
    }
    return count;
}

TEST(TokenBucket, ACostIsCoveredUpToTheLastTokenAndNotBeyond) {
    const Budget budget{{1.0, 100.0, 1.0}, {2.0, 100.0, 1.0}};
    TokenBucket bucket(budget, 0);
    EXPECT_TRUE(bucket.covers(budget, {2.0, 100.0, 1.0}));  // exactly what it holds
    bucket.charge({1.0, 0.5, 0.0});
    EXPECT_FALSE(bucket.covers(budget, {0.0, 100.0, 0.0}));  // half a byte short
    EXPECT_TRUE(bucket.covers(budget, {0.0, 99.5, 0.0}));
    EXPECT_FALSE(bucket.covers(budget, {2.0, 0.0, 0.0}));
    EXPECT_TRUE(bucket.covers(budget, {1.0, 0.0, 0.0}));
}

TEST(TokenBucket, TokensComeBackAtTheRateAndNeverAboveTheBurst) {
    const Budget budget{{10.0, 0.0, 0.0}, {5.0, 0.0, 0.0}};
    TokenBucket bucket(budget, 0);
    bucket.charge({5.0, 0.0, 0.0});
    bucket.refill(budget, kSecond / 10 - 1);  // one microsecond short of a whole token
    EXPECT_FALSE(bucket.covers(budget, kRequest));
    bucket.refill(budget, kSecond / 10);
    EXPECT_TRUE(bucket.covers(budget, kRequest));
    bucket.refill(budget, 60 * kSecond);
    EXPECT_DOUBLE_EQ(bucket.tokens().requests, 5.0);
}

TEST(TokenBucket, ACostLargerThanTheBurstPassesOnlyFromAFullBucketAndLeavesADebt) {
    const Budget budget{{0.0, 100.0, 0.0}, {0.0, 100.0, 0.0}};
    TokenBucket bucket(budget, 0);
    EXPECT_TRUE(bucket.covers(budget, {0.0, 250.0, 0.0}));
    bucket.charge({0.0, 250.0, 0.0});
    EXPECT_DOUBLE_EQ(bucket.tokens().bytes, -150.0);
    // The debt is repaid at the rate: 1.5 s to 0, 2.5 s to full again.
    bucket.refill(budget, 2'500'000 - 1);
    EXPECT_FALSE(bucket.covers(budget, {0.0, 250.0, 0.0}));
    bucket.refill(budget, 2'500'000);
    EXPECT_TRUE(bucket.covers(budget, {0.0, 250.0, 0.0}));
}

TEST(TokenBucket, ACpuDebtRefusesWhatNeedsCpuUntilItIsRepaidButNotWhatDoesNot) {
    const Budget budget{{10.0, 10.0, 0.5}, {10.0, 10.0, 1.0}};
    TokenBucket bucket(budget, 0);
    bucket.charge({0.0, 0.0, 1.5});  // measured after the work: half a second over
    EXPECT_FALSE(bucket.covers(budget, {1.0, 1.0, 1e-9}));
    EXPECT_TRUE(bucket.covers(budget, kRequest));  // a call with no document needs no CPU budget
    bucket.refill(budget, kSecond);                // 0.5 s of CPU back: at 0
    EXPECT_FALSE(bucket.covers(budget, {1.0, 1.0, 1e-9}));
    bucket.refill(budget, kSecond + 2);
    EXPECT_TRUE(bucket.covers(budget, {1.0, 1.0, 1e-9}));
}

TEST(Admission, AConnectionGetsItsShareOfItsUsersBurstThenIsRefusedNamingIt) {
    Admission admission(budgets());
    EXPECT_EQ(admitted(admission, ":1.1", 4, kSecond), 4);  // half of 8
    const auto refused = admission.admit(kUser, ":1.1", kRequest, kSecond);
    EXPECT_FALSE(refused.admitted);
    EXPECT_THAT(refused.refusal, StartsWith("too many requests from uid 1000: connection :1.1 "
                                            "has spent its share"));
    EXPECT_THAT(refused.refusal, HasSubstr("[limits] connection-share"));
}

TEST(Admission, AUsersConnectionsTogetherGetItsSharedBudgetThenOnlyQuietOnesTheReserve) {
    Admission admission(budgets());
    // The shared part is 6 requests (3/4 of 8): two connections spend it, 3 each, and their
    // fourth is refused by the user's budget (each is down to 1 of 4, below half: not quiet).
    EXPECT_EQ(admitted(admission, ":1.1", 3, kSecond), 3);
    EXPECT_EQ(admitted(admission, ":1.2", 3, kSecond), 3);
    const auto refused = admission.admit(kUser, ":1.1", kRequest, kSecond);
    EXPECT_FALSE(refused.admitted);
    EXPECT_THAT(refused.refusal, StartsWith("too many requests from uid 1000: its connections "
                                            "together have spent its budget"));
    // Another app of the same user, quiet until now, still gets the reserve: 2 requests (1/4
    // of 8), which leave its own bucket at 2 of 4 (half: still quiet)...
    const auto first = admission.admit(kUser, ":1.3", kRequest, kSecond);
    EXPECT_TRUE(first.admitted);
    EXPECT_EQ(first.charged_to, ChargedTo::reserve);
    EXPECT_TRUE(admission.admit(kUser, ":1.3", kRequest, kSecond).admitted);
    // ...and the third is refused: the reserve is spent.
    EXPECT_FALSE(admission.admit(kUser, ":1.3", kRequest, kSecond).admitted);
}

TEST(Admission, AConnectionThatWouldFallBelowHalfItsBucketIsNotQuiet) {
    Admission admission(budgets());
    EXPECT_EQ(admitted(admission, ":1.1", 4, kSecond), 4);
    EXPECT_EQ(admitted(admission, ":1.2", 2, kSecond), 2);  // the shared 6 are spent
    // :1.3 after one request holds 3 of 4, after two 2 of 4 (half: allowed); :1.2 holds 2 of 4,
    // after one more 1 of 4: below half, so the reserve is not for it.
    const auto below_half = admission.admit(kUser, ":1.2", kRequest, kSecond);
    EXPECT_FALSE(below_half.admitted);
    EXPECT_TRUE(admission.admit(kUser, ":1.3", kRequest, kSecond).admitted);
}

TEST(Admission, ARefusedRequestStillSpendsOneOfItsConnectionsRequestsButNeverBelowZero) {
    Admission admission(budgets());
    EXPECT_EQ(admitted(admission, ":1.1", 4, kSecond), 4);
    EXPECT_EQ(admitted(admission, ":1.1", 100, kSecond), 0);
    EXPECT_DOUBLE_EQ(admission.connection_tokens(":1.1", kSecond).requests, 0.0);
    // 4 a second for a connection: a quarter second brings one back, whatever it was refused.
    EXPECT_EQ(admitted(admission, ":1.1", 2, kSecond + kSecond / 4), 1);
}

TEST(Admission, DocumentBytesAreChargedBeforeTheWorkAndTheLastDocumentThatFitsPasses) {
    Admission admission(budgets());
    // A connection holds 2 MiB of documents: two 1 MiB documents pass, the third does not.
    EXPECT_EQ(admitted(admission, ":1.1", 2, kSecond, document(kMiB)), 2);
    const auto refused = admission.admit(kUser, ":1.1", document(1.0), kSecond);
    EXPECT_FALSE(refused.admitted);
    EXPECT_THAT(refused.refusal, StartsWith("too many document bytes from uid 1000"));
    // A call with no document still passes: its bytes are not what is short.
    EXPECT_TRUE(admission.admit(kUser, ":1.1", kRequest, kSecond).admitted);
    // 2 MiB a second for a connection: a quarter second brings back half a MiB (not enough),
    // half a second 1 MiB.
    EXPECT_FALSE(admission.admit(kUser, ":1.1", document(kMiB), kSecond + kSecond / 4).admitted);
    EXPECT_TRUE(admission.admit(kUser, ":1.1", document(kMiB), kSecond + kSecond / 2).admitted);
}

TEST(Admission, MeasuredCpuTimeIsChargedAfterwardsAndRefusesTheNextDocumentUntilRepaid) {
    Admission admission(budgets());
    const auto first = admission.admit(kUser, ":1.1", document(100.0), kSecond);
    ASSERT_TRUE(first.admitted);
    // The work took 0.75 s: the connection's 0.5 s of CPU is overdrawn by 0.25 s.
    admission.charge_after(kUser, ":1.1", first.charged_to, {0.0, 0.0, 0.75}, kSecond);
    const auto refused = admission.admit(kUser, ":1.1", document(100.0), kSecond);
    EXPECT_FALSE(refused.admitted);
    EXPECT_THAT(refused.refusal, StartsWith("too much CPU time spent on the work of uid 1000"));
    EXPECT_TRUE(admission.admit(kUser, ":1.1", kRequest, kSecond).admitted);
    // 0.5 s of CPU a second for a connection: after 0.5 s the 0.25 s debt is repaid but for the
    // probe of the first document (1 ns): still refused; 2 ms later, admitted.
    EXPECT_FALSE(admission.admit(kUser, ":1.1", document(100.0), kSecond + kSecond / 2).admitted);
    EXPECT_TRUE(
        admission.admit(kUser, ":1.1", document(100.0), kSecond + kSecond / 2 + 2000).admitted);
}

TEST(Admission, RootAndTheDaemonsOwnUserAreNeverCharged) {
    Admission admission(budgets());
    EXPECT_EQ(admitted(admission, ":1.1", 1000, kSecond, document(4 * kMiB), 0), 1000);
    EXPECT_EQ(admitted(admission, ":1.2", 1000, kSecond, kRequest, ::geteuid()), 1000);
    EXPECT_EQ(admission.connections(), 0u);
}

TEST(Admission, EachUserHasItsOwnBudget) {
    Admission admission(budgets());
    EXPECT_EQ(admitted(admission, ":1.1", 3, kSecond), 3);
    EXPECT_EQ(admitted(admission, ":1.2", 3, kSecond), 3);
    EXPECT_EQ(admitted(admission, ":1.3", 3, kSecond, kRequest, kUser + 1), 3);
}

TEST(Admission, ALeftConnectionsBucketsGoButItsUsersStay) {
    Admission admission(budgets());
    EXPECT_EQ(admitted(admission, ":1.1", 3, kSecond), 3);
    EXPECT_EQ(admitted(admission, ":1.2", 3, kSecond), 3);
    admission.forget(":1.1");
    admission.forget(":1.2");
    EXPECT_EQ(admission.connections(), 0u);
    // A new connection starts full, but its user's shared budget is spent: the reserve's 2.
    EXPECT_EQ(admitted(admission, ":1.4", 4, kSecond), 2);
}

TEST(Admission, NewBudgetsApplyToTheNextRequest) {
    Admission admission(budgets());
    EXPECT_EQ(admitted(admission, ":1.1", 4, kSecond), 4);
    AdmissionBudgets wider = budgets();
    wider.user.rate.requests = 80.0;  // a connection: 40 a second
    admission.set_budgets(wider);
    EXPECT_EQ(admitted(admission, ":1.1", 10, kSecond + kSecond / 20), 2);  // 50 ms at 40/s
}

TEST(AdmissionBudgets, EachLimitsKeyIsTakenInItsRangeAndRefusedJustOutsideIt) {
    AdmissionBudgets budgets;
    EXPECT_TRUE(budgets.set("document-bytes-per-second", "1"));
    EXPECT_TRUE(budgets.set("document-burst-bytes", "1073741824"));
    EXPECT_TRUE(budgets.set("work-cpu-per-second", "0.001"));
    EXPECT_TRUE(budgets.set("work-cpu-burst", "60"));
    EXPECT_TRUE(budgets.set("connection-share", "1"));
    EXPECT_DOUBLE_EQ(budgets.user.rate.bytes, 1.0);
    EXPECT_DOUBLE_EQ(budgets.user.burst.bytes, 1073741824.0);
    EXPECT_DOUBLE_EQ(budgets.user.rate.cpu_s, 0.001);
    EXPECT_DOUBLE_EQ(budgets.user.burst.cpu_s, 60.0);
    EXPECT_DOUBLE_EQ(budgets.connection_share, 1.0);
    EXPECT_THROW(budgets.set("document-bytes-per-second", "0.999"), std::invalid_argument);
    EXPECT_THROW(budgets.set("document-burst-bytes", "1073741825"), std::invalid_argument);
    EXPECT_THROW(budgets.set("work-cpu-per-second", "1.001"), std::invalid_argument);
    EXPECT_THROW(budgets.set("work-cpu-burst", "60.001"), std::invalid_argument);
    EXPECT_THROW(budgets.set("connection-share", "0.009"), std::invalid_argument);
    try {
        budgets.set("connection-share", "half");
        FAIL() << "no error";
    } catch (const std::invalid_argument& error) {
        EXPECT_EQ(std::string(error.what()),
                  "connection-share = \"half\" is not a number from 0.01 to 1");
    }
    EXPECT_FALSE(budgets.set("max-on-time", "30"));  // PlaybackLimits' key, not ours
}

}  // namespace
}  // namespace vibscore::daemon
