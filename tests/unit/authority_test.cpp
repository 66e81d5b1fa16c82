// Who may do what, without a bus: polkit's answer through a fake of the PolkitAuthority seam,
// root, the group rule where polkit is not running, and the shipped polkit actions.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include <string>

#include "daemon/authority.hpp"
#include "daemon/request_error.hpp"
#include "tests/fakes/fake_polkit_authority.hpp"
#include "tests/support/run_command.hpp"

namespace vibscore::daemon {
namespace {

using vibscore::testing::FakePolkitAuthority;

Caller user(uid_t uid, bool in_group_vibscore = false) {
    return Caller{":1.42", uid, in_group_vibscore};
}

std::string refusal(const Authorizer& authorizer, const Caller& caller, Action action) {
    try {
        authorizer.require(caller, action, "Compose");
    } catch (const RequestError& error) {
        EXPECT_EQ(error.code(), RequestError::Code::permission_denied);
        return error.what();
    }
    return "<allowed>";
}

class AuthorityTest : public ::testing::Test {
  protected:
    FakePolkitAuthority polkit;
    Authorizer authorizer{polkit};
};

TEST_F(AuthorityTest, RootIsAllowedEverythingWithoutAskingPolkit) {
    for (const auto action : {Action::compose, Action::manage, Action::urgent_usage}) {
        EXPECT_TRUE(authorizer.allowed(user(0), action));
    }
    EXPECT_TRUE(polkit.asked.empty());
}

TEST_F(AuthorityTest, PolkitIsAskedAboutTheCallersBusConnectionAndTheAction) {
    polkit.answers["org.vibscore.compose"] = PolkitAnswer::authorized;
    EXPECT_TRUE(authorizer.allowed(user(1000), Action::compose));
    EXPECT_FALSE(authorizer.allowed(user(1000), Action::manage));
    ASSERT_EQ(polkit.asked.size(), 2u);
    EXPECT_EQ(polkit.asked[0],
              std::make_pair(std::string(":1.42"), std::string("org.vibscore.compose")));
    EXPECT_EQ(polkit.asked[1].second, "org.vibscore.manage");
}

TEST_F(AuthorityTest, WithPolkitRunningGroupVibscoreGrantsNothingByItself) {
    EXPECT_FALSE(authorizer.allowed(user(1000, true), Action::compose));
    EXPECT_EQ(refusal(authorizer, user(1000, true), Action::compose),
              "Compose needs org.vibscore.compose, which polkit does not grant to uid 1000");
}

TEST_F(AuthorityTest, WithoutPolkitRootAndGroupVibscoreMayAndOthersMayNot) {
    polkit.on_the_bus = false;
    EXPECT_TRUE(authorizer.allowed(user(1000, true), Action::urgent_usage));
    EXPECT_FALSE(authorizer.allowed(user(1001), Action::urgent_usage));
    EXPECT_EQ(refusal(authorizer, user(1001), Action::manage),
              "Compose needs org.vibscore.manage; polkit is not running, so only root and group "
              "vibscore have it, and uid 1001 is neither");
}

TEST_F(AuthorityTest, APolkitThatFailsRefusesAndSaysWhy) {
    polkit.failure = "org.freedesktop.DBus.Error.NoReply: timed out";
    EXPECT_FALSE(authorizer.allowed(user(1000, true), Action::compose));
    EXPECT_EQ(refusal(authorizer, user(1000, true), Action::urgent_usage),
              "Compose needs org.vibscore.urgent-usage, and polkit could not check it for uid "
              "1000: org.freedesktop.DBus.Error.NoReply: timed out");
}

TEST(Authority, OnlyRingtoneAndAlarmAreUrgentUsages) {
    for (const auto usage : {Usage::ringtone, Usage::alarm}) {
        EXPECT_TRUE(needs_urgent_usage(usage));
    }
    for (const auto usage : {Usage::notification, Usage::communication, Usage::accessibility,
                             Usage::hardware_feedback, Usage::touch, Usage::media}) {
        EXPECT_FALSE(needs_urgent_usage(usage));
    }
}

// The shipped actions file: each action the daemon asks about, with the defaults docs/daemon.md
// promises, and user vibscore (the daemon) allowed to ask polkit about other users' calls.
TEST(Authority, TheShippedPolicyDeclaresEachActionWithItsDefaults) {
    pugi::xml_document policy;
    const auto path = vibscore::testing::required_env("VIBSCORE_POLKIT_POLICY");
    ASSERT_TRUE(policy.load_file(path.c_str())) << path;
    struct Expected {
        Action action;
        const char *any, *inactive, *active;
    };
    for (const auto& [action, any, inactive, active] :
         {Expected{Action::compose, "auth_admin", "auth_admin", "yes"},
          Expected{Action::manage, "auth_admin", "auth_admin", "auth_admin"},
          Expected{Action::urgent_usage, "no", "no", "yes"}}) {
        const std::string id(action_id(action));
        const auto node =
            policy.child("policyconfig").find_child_by_attribute("action", "id", id.c_str());
        ASSERT_TRUE(node) << id;
        const auto defaults = node.child("defaults");
        EXPECT_STREQ(defaults.child_value("allow_any"), any) << id;
        EXPECT_STREQ(defaults.child_value("allow_inactive"), inactive) << id;
        EXPECT_STREQ(defaults.child_value("allow_active"), active) << id;
        EXPECT_STREQ(
            node.find_child_by_attribute("annotate", "key", "org.freedesktop.policykit.owner")
                .child_value(),
            "unix-user:vibscore")
            << id;
    }
    EXPECT_EQ(policy.child("policyconfig").select_nodes("action").size(), 3u);
}

}  // namespace
}  // namespace vibscore::daemon
