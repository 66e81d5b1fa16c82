// Who is privileged, without a bus: the group check (what a caller may spend: admission_test).
#include <gtest/gtest.h>

#include <pwd.h>

#include "daemon/callers.hpp"

namespace vibscore::daemon {
namespace {

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
