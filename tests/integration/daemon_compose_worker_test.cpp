// Issue 33, item 1: the bus thread never parses or validates a caller's document. Compose's
// document is parsed, bound and checked against the registry on a worker; only the store is
// written on the bus thread; its reply, the document stored or the named error, comes when the
// worker is done. The real vibscored on a private bus.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sdbus-c++/sdbus-c++.h>

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include "bench/flood.hpp"
#include "dbus/sdbus_compat.hpp"
#include "score/limits.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;
using testing::wait_until;

constexpr const char* kInterface = "org.vibscore.Haptics1";
constexpr const char* kPath = "/org/vibscore/Haptics1";

// A large score whose last bar plays a string lra-phone does not have: refused only once the
// whole document has been parsed and its bars bound to the clef, the most work a refusal costs.
std::string score_invalid_at_its_end(std::size_t bytes) {
    auto score = bench::inline_score_of(bytes);
    const std::string tail = "</VibScore>";
    score.insert(score.size() - tail.size(),
                 "<Bar clef=\"l\"><Note length=\"whole\" number=\"1\" string=\"99\"/></Bar>");
    return score;
}

// A valid score of exactly `bytes`, padded with a comment after its root element.
std::string valid_score_of_exactly(std::size_t bytes) {
    auto score = bench::inline_score_of(bytes);
    const std::string open = "<!--", close = "-->";
    score += open + std::string(bytes - score.size() - open.size() - close.size(), ' ') + close;
    return score;
}

// The Compose replies of one connection, as they come.
struct ComposeReplies {
    std::mutex mutex;
    std::vector<std::string> errors;  // "" for a document stored
    std::atomic<int> count{0};

    void record(const sdbus::Error* error) {
        {
            const std::lock_guard lock(mutex);
            errors.push_back(error == nullptr
                                 ? std::string()
                                 : dbus::error_name(*error) + ": " + error->getMessage());
        }
        ++count;
    }
};

void compose_async(sdbus::IProxy& proxy, const std::string& name, const std::string& document,
                   ComposeReplies& replies) {
    proxy.callMethodAsync("Compose")
        .onInterface(kInterface)
        .withArguments(name, document)
        .uponReplyInvoke(
            [&replies](dbus::AsyncCallError error) { replies.record(dbus::failure_of(error)); });
}

TEST(DaemonComposeWorker, AnotherCallersListIsAnsweredWhileLargeComposesAreBeingParsed) {
    DaemonFixture daemon;
    // Another caller, connected before the Composes go out.
    auto other = daemon.client();
    ASSERT_NO_THROW(other->List("score"));

    auto connection = sdbus::createSystemBusConnection();
    connection->enterEventLoopAsync();
    auto proxy = dbus::create_proxy(*connection, kInterface, kPath);
    constexpr int kComposes = 8;
    const auto document = score_invalid_at_its_end(limits::document_bytes - 1024);
    ComposeReplies replies;
    for (int i = 0; i < kComposes; ++i) {
        compose_async(*proxy, "big-" + std::to_string(i), document, replies);
    }
    // The daemon answers a connection's messages in the order they came: once this Ping is
    // answered, the bus thread has taken every one of the Composes before it. Had it parsed
    // them, their replies would all have come first.
    proxy->callMethod("Ping").onInterface("org.freedesktop.DBus.Peer");
    EXPECT_LT(replies.count.load(), kComposes) << "the Composes were done on the bus thread";

    // Another caller is answered while the worker is still parsing.
    const auto listed = other->List("score");
    EXPECT_LT(replies.count.load(), kComposes)
        << "List was answered only after every Compose had been parsed";
    EXPECT_FALSE(listed.empty());

    // Each Compose is answered in the end, with the error it had before the worker.
    ASSERT_TRUE(
        wait_until([&] { return replies.count.load() == kComposes; }, std::chrono::seconds(60)))
        << replies.count.load() << " of " << kComposes << " answered\n"
        << daemon.daemon_log();
    const std::lock_guard lock(replies.mutex);
    for (const auto& error : replies.errors) {
        EXPECT_THAT(error, HasSubstr("org.vibscore.Haptics1.Error.InvalidDocument: "));
        EXPECT_THAT(error, HasSubstr("string \"99\" is out of range (1 to 6)"));
    }
    for (int i = 0; i < kComposes; ++i) {
        EXPECT_EQ(daemon.call({"Origin", "ss", "score", "big-" + std::to_string(i)}).exit_code, 1)
            << "a refused document is not stored";
    }
}

// The size limit at its edge, checked on the worker: the largest document is stored, one byte
// more is refused with LimitExceeded naming both sizes, and neither waits for the other.
TEST(DaemonComposeWorker, TheDocumentLimitIsTheSameAtItsEdge) {
    DaemonFixture daemon;
    auto client = daemon.client();
    const auto largest = valid_score_of_exactly(limits::document_bytes);
    ASSERT_EQ(largest.size(), limits::document_bytes);
    EXPECT_NO_THROW(client->Compose("largest", largest));
    EXPECT_EQ(client->Get("score", "largest"), largest);
    EXPECT_TRUE(client->wait_for([](const testing::SeenSignal& seen) {
        return seen.name == "RegistryChanged";
    })) << "RegistryChanged after a Compose done on the worker";

    try {
        client->Compose("too-large", largest + " ");
        ADD_FAILURE() << "a document one byte over the limit was stored";
    } catch (const sdbus::Error& error) {
        EXPECT_EQ(dbus::error_name(error), "org.vibscore.Haptics1.Error.LimitExceeded");
        EXPECT_THAT(error.getMessage(),
                    HasSubstr("is " + std::to_string(limits::document_bytes + 1) +
                              " bytes; the limit is " + std::to_string(limits::document_bytes)));
    }
    EXPECT_EQ(daemon.call({"Origin", "ss", "score", "too-large"}).exit_code, 1);
}

// Composes that overtake one another (a clef, then a score that uses it) are each checked
// against the registry as the one before left it.
TEST(DaemonComposeWorker, AScoreComposedAfterItsClefBindsToIt) {
    DaemonFixture daemon;
    auto client = daemon.client();
    client->Compose("my-clef", client->Get("clef", "lra-phone"));
    client->Compose("my-score",
                    "<VibScore><Title>mine</Title><Clef id=\"c\" href=\"my-clef.clef.xml\"/>"
                    "<Bar clef=\"c\"><Note length=\"quarter\" number=\"1\" string=\"1\"/></Bar>"
                    "</VibScore>");
    EXPECT_EQ(client->Origin("score", "my-score"), "stored");
    try {
        client->Delete("clef", "my-clef");
        ADD_FAILURE() << "a clef a score uses was deleted";
    } catch (const sdbus::Error& error) {
        EXPECT_EQ(dbus::error_name(error), "org.vibscore.Haptics1.Error.Busy");
        EXPECT_THAT(error.getMessage(), HasSubstr("my-score"));
    }
}

// BarClefs of an inline score is answered from the worker too, with the bars or the error.
TEST(DaemonComposeWorker, BarClefsOfAnInlineScoreIsAnsweredFromTheWorker) {
    DaemonFixture daemon;
    auto client = daemon.client();
    const auto bars = client->BarClefs(bench::inline_score_of(4096));
    ASSERT_FALSE(bars.empty());
    EXPECT_EQ(bars.front().get<0>(), "lra-phone");
    EXPECT_EQ(bars.size(), client->BarClefs(bench::inline_score_of(4096)).size());
    try {
        client->BarClefs(score_invalid_at_its_end(4096));
        ADD_FAILURE() << "an invalid inline score was answered";
    } catch (const sdbus::Error& error) {
        EXPECT_EQ(dbus::error_name(error), "org.vibscore.Haptics1.Error.InvalidDocument");
        EXPECT_THAT(error.getMessage(), HasSubstr("string \"99\" is out of range (1 to 6)"));
    }
    // A registry score's name is answered as before.
    EXPECT_FALSE(client->BarClefs("success").empty());
}

// A caller over its document budget is refused before its document is parsed, by BarClefs as by
// Play: LimitExceeded naming the budget, and its other calls go on.
TEST(DaemonComposeWorker, BarClefsOverTheDocumentBudgetIsRefusedNamingIt) {
    constexpr uid_t kNobody = 65534;
    DaemonFixture daemon{"[limits]\ndocument-bytes-per-second = 1\ndocument-burst-bytes = 65536\n"};
    const auto score = bench::inline_score_of(40000);
    const auto first = daemon.call({"BarClefs", "s", score}, kNobody);
    EXPECT_EQ(first.exit_code, 0) << first.err;
    std::string refused;
    for (int i = 0; i < 4 && refused.empty(); ++i) {
        const auto again = daemon.call({"BarClefs", "s", score}, kNobody);
        if (again.exit_code != 0) {
            refused = again.err;
        }
    }
    EXPECT_THAT(refused, HasSubstr("too many document bytes from uid 65534"));
    const auto listed = daemon.call({"List", "s", "score"}, kNobody);
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
}

}  // namespace
}  // namespace vibscore
