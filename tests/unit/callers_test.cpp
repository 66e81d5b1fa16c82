// Who may call and how often, without a bus: the per-user token bucket and the group check.
#include <gtest/gtest.h>

#include <pwd.h>

#include "daemon/callers.hpp"

namespace vibscore::daemon {
namespace {

constexpr std::uint64_t kSecond = 1'000'000;

int admitted(CallerDirectory& callers, uid_t uid, int tries, std::uint64_t at) {
    int count = 0;
    for (int i = 0; i < tries; ++i) {
        count += callers.admit(uid, at) ? 1 : 0;
    }
    return count;
}

TEST(RateLimit, AUserGetsItsBurstAtOnceThenIsRefused) {
    CallerDirectory callers(10.0, 5.0);
    EXPECT_EQ(admitted(callers, 1000, 8, 100 * kSecond), 5);
}

TEST(RateLimit, TokensComeBackAtTheRateUpToTheBurst) {
    CallerDirectory callers(10.0, 5.0);
    const std::uint64_t start = 100 * kSecond;
    admitted(callers, 1000, 5, start);
    EXPECT_EQ(admitted(callers, 1000, 5, start + kSecond / 10), 1);  // 0.1 s: one token
    EXPECT_EQ(admitted(callers, 1000, 5, start + kSecond / 10 + kSecond / 5), 2);
    EXPECT_EQ(admitted(callers, 1000, 20, start + 60 * kSecond), 5);  // never above the burst
}

// The edge: a request needs a whole token. 0.95 s after the bucket ran dry at 1 per second,
// 0.95 of a token is there: refused; at 1.0 s: admitted.
TEST(RateLimit, AlmostAWholeTokenIsRefusedAndAWholeOneAdmitted) {
    CallerDirectory callers(1.0, 1.0);
    const std::uint64_t start = 100 * kSecond;
    EXPECT_EQ(admitted(callers, 1000, 1, start), 1);
    EXPECT_EQ(admitted(callers, 1000, 1, start + kSecond / 2), 0);  // half a token
    EXPECT_EQ(admitted(callers, 1000, 1, start + kSecond * 95 / 100), 0);
    EXPECT_EQ(admitted(callers, 1000, 1, start + kSecond), 1);
}

TEST(RateLimit, EachUserHasItsOwnBucket) {
    CallerDirectory callers(1.0, 2.0);
    EXPECT_EQ(admitted(callers, 1000, 3, kSecond), 2);
    EXPECT_EQ(admitted(callers, 1001, 3, kSecond), 2);
}

// Twenty connections of one user are one caller: the bucket is the user's, and leaving the bus
// and coming back does not refill it.
TEST(RateLimit, AUsersConnectionsShareOneBucketThatReconnectingDoesNotRefill) {
    CallerDirectory callers(1.0, 2.0, [](const std::string& sender) {
        return sender == ":1.9" ? uid_t{1001} : uid_t{1000};
    });
    EXPECT_EQ(admitted(callers, 1000, 1, kSecond), 1);
    callers.forget(":1.1");
    EXPECT_EQ(admitted(callers, 1000, 3, kSecond), 1);
}

TEST(RateLimit, RootIsNeverLimited) {
    CallerDirectory callers(1.0, 1.0);
    EXPECT_EQ(admitted(callers, 0, 100, kSecond), 100);
}

TEST(RateLimit, ANewRateAppliesToTheNextRequest) {
    CallerDirectory callers(1.0, 1.0);
    admitted(callers, 1000, 1, kSecond);
    callers.set_rate(100.0, 10.0);
    EXPECT_EQ(callers.requests_per_second(), 100.0);
    EXPECT_EQ(admitted(callers, 1000, 20, kSecond + kSecond / 20), 5);  // 50 ms at 100/s
}

TEST(Privilege, RootIsInEveryGroupEvenOneThatDoesNotExist) {
    EXPECT_TRUE(user_in_group(0, "vibscore-no-such-group"));
}

TEST(Privilege, AUserIsInItsPrimaryGroupAndNotInOthers) {
    const passwd* nobody = getpwnam("nobody");
    ASSERT_NE(nobody, nullptr) << "Debian always has user nobody";
    EXPECT_TRUE(user_in_group(nobody->pw_uid, "nogroup"));
    EXPECT_FALSE(user_in_group(nobody->pw_uid, "root"));
    EXPECT_FALSE(user_in_group(nobody->pw_uid, "vibscore-no-such-group"));
}

TEST(Privilege, AUidThatIsNoUserIsInNoGroup) {
    EXPECT_FALSE(user_in_group(4'000'000'000u, "nogroup"));
}

}  // namespace
}  // namespace vibscore::daemon
