// Who may do what, without a bus: polkit's answer through a fake of the PolkitAuthority seam,
// root, the group rule where polkit is not running, and the shipped polkit actions.
#include <gtest/gtest.h>

#include <memory>

#include <pugixml.hpp>

#include <optional>
#include <string>

#include "daemon/authority.hpp"
#include "daemon/request_error.hpp"
#include "tests/fakes/fake_polkit_authority.hpp"
#include "tests/support/run_command.hpp"

namespace vibscore::daemon {
namespace {

using vibscore::testing::FakePolkitAuthority;

Caller user(uid_t uid, bool in_group_vibscore = false, std::string sender = ":1.42") {
    return Caller{std::move(sender), uid, in_group_vibscore};
}

class AuthorityTest : public ::testing::Test {
  protected:
    FakePolkitAuthority polkit;
    Authorizer authorizer{polkit, 3};

    // The decision, when it came before this returns; nullopt while polkit has not answered.
    std::optional<Decision> decide(const Caller& caller, Action action) {
        // Shared: a held question is answered after this returns.
        auto decided = std::make_shared<std::optional<Decision>>();
        authorizer.decide(caller, action,
                          [decided](const Decision& decision) { *decided = decision; });
        return *decided;
    }
    bool allowed(const Caller& caller, Action action) {
        const auto decision = decide(caller, action);
        return decision && decision->allowed();
    }
    std::string refusal(const Caller& caller, Action action) {
        const auto decision = decide(caller, action);
        if (!decision) {
            return "<undecided>";
        }
        try {
            decision->require("Compose");
        } catch (const RequestError& error) {
            return error.what();
        }
        return "<allowed>";
    }
};

TEST_F(AuthorityTest, RootIsAllowedEverythingWithoutAskingPolkit) {
    for (const auto action : {Action::compose, Action::manage, Action::urgent_usage}) {
        EXPECT_TRUE(allowed(user(0), action));
        EXPECT_TRUE(authorizer.known(user(0), action)->allowed());
    }
    EXPECT_TRUE(polkit.asked.empty());
}

TEST_F(AuthorityTest, PolkitIsAskedAboutTheCallersBusConnectionAndTheAction) {
    polkit.answers["org.vibscore.compose"] = PolkitAnswer::authorized;
    EXPECT_TRUE(allowed(user(1000), Action::compose));
    EXPECT_FALSE(allowed(user(1000), Action::manage));
    ASSERT_EQ(polkit.asked.size(), 2u);
    EXPECT_EQ(polkit.asked[0],
              std::make_pair(std::string(":1.42"), std::string("org.vibscore.compose")));
    EXPECT_EQ(polkit.asked[1].second, "org.vibscore.manage");
}

TEST_F(AuthorityTest, WithPolkitRunningGroupVibscoreGrantsNothingByItself) {
    EXPECT_FALSE(allowed(user(1000, true), Action::compose));
    EXPECT_EQ(refusal(user(1000, true), Action::compose),
              "Compose needs org.vibscore.compose, which polkit does not grant to uid 1000");
}

TEST_F(AuthorityTest, WithoutPolkitRootAndGroupVibscoreMayAndOthersMayNot) {
    polkit.on_the_bus = false;
    EXPECT_TRUE(allowed(user(1000, true), Action::urgent_usage));
    EXPECT_FALSE(allowed(user(1001), Action::urgent_usage));
    EXPECT_EQ(refusal(user(1001), Action::manage),
              "Compose needs org.vibscore.manage; polkit is not running, so only root and group "
              "vibscore have it, and uid 1001 is neither");
}

TEST_F(AuthorityTest, APolkitThatFailsRefusesAndSaysWhy) {
    polkit.failure = "org.freedesktop.DBus.Error.NoReply: timed out";
    EXPECT_FALSE(allowed(user(1000, true), Action::compose));
    EXPECT_EQ(refusal(user(1000, true), Action::urgent_usage),
              "Compose needs org.vibscore.urgent-usage, and polkit could not check it for uid "
              "1000: org.freedesktop.DBus.Error.NoReply: timed out");
}

// Nothing waits for polkit: the decision comes when polkit answers, and meanwhile others are
// decided (root at once, another caller's own question asked).
TEST_F(AuthorityTest, TheDecisionComesWhenPolkitAnswersAndNobodyWaitsMeanwhile) {
    polkit.hold = true;
    polkit.answers["org.vibscore.urgent-usage"] = PolkitAnswer::authorized;
    std::optional<Decision> decided;
    authorizer.decide(user(1000), Action::urgent_usage,
                      [&](const Decision& decision) { decided = decision; });
    EXPECT_FALSE(decided);
    EXPECT_FALSE(authorizer.known(user(1000), Action::urgent_usage));
    EXPECT_TRUE(allowed(user(0), Action::manage));
    EXPECT_FALSE(decide(user(1001, false, ":1.7"), Action::compose));
    EXPECT_EQ(polkit.held(), 2u);
    polkit.answer_held();
    ASSERT_TRUE(decided);
    EXPECT_TRUE(decided->allowed());
}

// As polkit's own clients do, an answer is kept for the connection's lifetime: asked once.
TEST_F(AuthorityTest, PolkitsAnswerIsKeptForTheConnectionUntilItLeaves) {
    polkit.answers["org.vibscore.compose"] = PolkitAnswer::authorized;
    EXPECT_TRUE(allowed(user(1000), Action::compose));
    EXPECT_TRUE(allowed(user(1000), Action::compose));
    EXPECT_EQ(polkit.asked.size(), 1u);
    EXPECT_TRUE(authorizer.known(user(1000), Action::compose)->allowed());
    // A refusal is kept too, and per action.
    EXPECT_FALSE(allowed(user(1000), Action::manage));
    EXPECT_FALSE(allowed(user(1000), Action::manage));
    EXPECT_EQ(polkit.asked.size(), 2u);
    // Another connection of the same user is asked about afresh.
    EXPECT_TRUE(allowed(user(1000, false, ":1.43"), Action::compose));
    EXPECT_EQ(polkit.asked.size(), 3u);
    authorizer.forget(":1.42");
    EXPECT_FALSE(authorizer.known(user(1000), Action::compose));
    EXPECT_TRUE(allowed(user(1000), Action::compose));
    EXPECT_EQ(polkit.asked.size(), 4u);
}

// A failure and "polkit is not on the bus" are not kept: polkit may recover, or start.
TEST_F(AuthorityTest, AFailureOrAnAbsentPolkitIsAskedAgainNextTime) {
    polkit.failure = "org.freedesktop.DBus.Error.NoReply: timed out";
    EXPECT_FALSE(allowed(user(1000), Action::compose));
    polkit.failure.clear();
    polkit.on_the_bus = false;
    EXPECT_FALSE(allowed(user(1000), Action::compose));
    EXPECT_FALSE(authorizer.known(user(1000), Action::compose));
    polkit.on_the_bus = true;
    polkit.answers["org.vibscore.compose"] = PolkitAnswer::authorized;
    EXPECT_TRUE(allowed(user(1000), Action::compose));
    EXPECT_EQ(polkit.asked.size(), 3u);
}

TEST_F(AuthorityTest, QuestionsOpenAtOnceAboutOneConnectionAndActionShareOneAnswer) {
    polkit.hold = true;
    int decisions = 0;
    for (int i = 0; i < 5; ++i) {
        authorizer.decide(user(1000), Action::compose, [&](const Decision&) { ++decisions; });
    }
    EXPECT_EQ(polkit.held(), 1u);
    polkit.answer_held();
    EXPECT_EQ(decisions, 5);
}

// The limit is 3 open questions per user here: the third is asked, the fourth refused at once
// as LimitExceeded; another user is not affected; once answered, the user may ask again.
TEST_F(AuthorityTest, AUserMayHaveAtMostTheLimitOfQuestionsOpenAtOnce) {
    polkit.hold = true;
    for (const auto* sender : {":1.1", ":1.2", ":1.3"}) {
        EXPECT_FALSE(decide(user(1000, false, sender), Action::compose));
    }
    EXPECT_EQ(polkit.held(), 3u);
    const auto refused = decide(user(1000, false, ":1.4"), Action::compose);
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->verdict(), Decision::Verdict::too_many_pending);
    try {
        refused->require("Compose");
        ADD_FAILURE() << "allowed";
    } catch (const RequestError& error) {
        EXPECT_EQ(error.code(), RequestError::Code::limit_exceeded);
        EXPECT_EQ(std::string(error.what()),
                  "Compose needs org.vibscore.compose, and uid 1000 already waits for polkit's "
                  "answer to 3 questions: try again when they are answered");
    }
    EXPECT_FALSE(decide(user(1001, false, ":1.5"), Action::compose));
    EXPECT_EQ(polkit.held(), 4u);
    polkit.answer_held();
    EXPECT_EQ(authorizer.pending(), 0u);
    EXPECT_FALSE(decide(user(1000, false, ":1.6"), Action::compose));  // asked, not refused
    EXPECT_EQ(polkit.held(), 1u);
}

// The caller left before polkit answered: its answer goes to nobody and is not kept.
TEST_F(AuthorityTest, AnAnswerForACallerThatLeftGoesToNobody) {
    polkit.hold = true;
    polkit.answers["org.vibscore.compose"] = PolkitAnswer::authorized;
    int decisions = 0;
    authorizer.decide(user(1000), Action::compose, [&](const Decision&) { ++decisions; });
    authorizer.forget(":1.42");
    polkit.answer_held();
    EXPECT_EQ(decisions, 0);
    EXPECT_FALSE(authorizer.known(user(1000), Action::compose));
    EXPECT_EQ(authorizer.pending(), 0u);
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
