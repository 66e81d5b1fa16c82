// Who may call and how often, without a bus: the per-caller token bucket and the group check.
#include <gtest/gtest.h>

#include <pwd.h>

#include "daemon/callers.hpp"

namespace vibscore::daemon {
namespace {

constexpr std::uint64_t kSecond = 1'000'000;

int admitted(CallerDirectory& callers, const std::string& sender, int tries, std::uint64_t at) {
    int count = 0;
    for (int i = 0; i < tries; ++i) {
        count += callers.admit(sender, at) ? 1 : 0;
    }
    return count;
}

TEST(RateLimit, ACallerGetsItsBurstAtOnceThenIsRefused) {
    CallerDirectory callers(10.0, 5.0);
    EXPECT_EQ(admitted(callers, ":1.1", 8, 100 * kSecond), 5);
}

TEST(RateLimit, TokensComeBackAtTheRateUpToTheBurst) {
    CallerDirectory callers(10.0, 5.0);
    const std::uint64_t start = 100 * kSecond;
    admitted(callers, ":1.1", 5, start);
    EXPECT_EQ(admitted(callers, ":1.1", 5, start + kSecond / 10), 1);  // 0.1 s: one token
    EXPECT_EQ(admitted(callers, ":1.1", 5, start + kSecond / 10 + kSecond / 5), 2);
    EXPECT_EQ(admitted(callers, ":1.1", 20, start + 60 * kSecond), 5);  // never above the burst
}

TEST(RateLimit, EachCallerHasItsOwnBucket) {
    CallerDirectory callers(1.0, 2.0);
    EXPECT_EQ(admitted(callers, ":1.1", 3, kSecond), 2);
    EXPECT_EQ(admitted(callers, ":1.2", 3, kSecond), 2);
}

TEST(RateLimit, ACallerThatLeftAndCameBackStartsWithAFullBucket) {
    CallerDirectory callers(1.0, 2.0);
    admitted(callers, ":1.1", 2, kSecond);
    callers.forget(":1.1");
    EXPECT_EQ(admitted(callers, ":1.1", 3, kSecond), 2);
}

TEST(RateLimit, ANewRateAppliesToTheNextRequest) {
    CallerDirectory callers(1.0, 1.0);
    admitted(callers, ":1.1", 1, kSecond);
    callers.set_rate(100.0, 10.0);
    EXPECT_EQ(callers.requests_per_second(), 100.0);
    EXPECT_EQ(admitted(callers, ":1.1", 20, kSecond + kSecond / 20), 5);  // 50 ms at 100/s
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
