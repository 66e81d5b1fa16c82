// The fair worker (issue 33, item 1): jobs taken round-robin across users and, within a user,
// across connections; each bound at its edge (the last job queued, the first refused).
#include "daemon/work_queue.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

#include "tests/support/wait_until.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::ElementsAre;
using testing::wait_until;

// A job that holds its worker until released, so that what is pushed meanwhile waits.
class Gate {
  public:
    std::function<void()> job() {
        return [this] {
            std::unique_lock lock(mutex_);
            entered_ = true;
            open_.wait(lock, [this] { return released_; });
        };
    }
    bool entered() {
        const std::lock_guard lock(mutex_);
        return entered_;
    }
    void release() {
        {
            const std::lock_guard lock(mutex_);
            released_ = true;
        }
        open_.notify_all();
    }

  private:
    std::mutex mutex_;
    std::condition_variable open_;
    bool entered_ = false;
    bool released_ = false;
};

// What ran, in order.
class Record {
  public:
    std::function<void()> job(std::string name) {
        return [this, name = std::move(name)] {
            const std::lock_guard lock(mutex_);
            ran_.push_back(name);
        };
    }
    std::vector<std::string> ran() {
        const std::lock_guard lock(mutex_);
        return ran_;
    }

  private:
    std::mutex mutex_;
    std::vector<std::string> ran_;
};

TEST(FairWorkQueue, TakesJobsRoundRobinAcrossUsersAndWithinAUserAcrossConnections) {
    FairWorkQueue queue({1, 8, 256});
    Gate gate;
    Record record;
    ASSERT_EQ(queue.push(1, ":g", gate.job()), FairWorkQueue::Pushed::queued);
    ASSERT_TRUE(wait_until([&] { return gate.entered(); }));
    // User 1000 floods from :a (three jobs) and has one job on :b; user 1001 has one on :c.
    for (const char* name : {"a1", "a2", "a3"}) {
        queue.push(1000, ":a", record.job(name));
    }
    queue.push(1000, ":b", record.job("b1"));
    queue.push(1001, ":c", record.job("c1"));
    gate.release();
    ASSERT_TRUE(wait_until([&] { return record.ran().size() == 5; }));
    // :a's first, then the other user's, then the same user's other app, then :a's rest.
    EXPECT_THAT(record.ran(), ElementsAre("a1", "c1", "b1", "a2", "a3"));
}

TEST(FairWorkQueue, AConnectionMayHaveItsBoundOfJobsAndTheNextIsRefused) {
    FairWorkQueue queue({1, 3, 256});
    Gate gate;
    ASSERT_EQ(queue.push(1000, ":a", gate.job()), FairWorkQueue::Pushed::queued);  // running
    ASSERT_TRUE(wait_until([&] { return gate.entered(); }));
    Record record;
    EXPECT_EQ(queue.push(1000, ":a", record.job("2")), FairWorkQueue::Pushed::queued);
    EXPECT_EQ(queue.push(1000, ":a", record.job("3")), FairWorkQueue::Pushed::queued);  // the last
    EXPECT_EQ(queue.push(1000, ":a", record.job("4")), FairWorkQueue::Pushed::connection_full);
    // Another connection of the same user is not refused.
    EXPECT_EQ(queue.push(1000, ":b", record.job("b")), FairWorkQueue::Pushed::queued);
    EXPECT_EQ(queue.pending(":a"), 3u);
    gate.release();
    ASSERT_TRUE(wait_until([&] { return queue.pending(":a") == 0 && queue.pending(":b") == 0; }));
    // Done, the connection may queue again.
    EXPECT_EQ(queue.push(1000, ":a", record.job("5")), FairWorkQueue::Pushed::queued);
    EXPECT_TRUE(wait_until([&] { return record.ran().size() == 4; }));
}

TEST(FairWorkQueue, TheWholeQueueHoldsItsBoundOfWaitingJobsAndRefusesTheNext) {
    FairWorkQueue queue({1, 8, 4});
    Gate gate;
    ASSERT_EQ(queue.push(1, ":g", gate.job()), FairWorkQueue::Pushed::queued);
    ASSERT_TRUE(wait_until([&] { return gate.entered(); }));  // running: no longer waiting
    Record record;
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(queue.push(static_cast<uid_t>(1000 + i), ":" + std::to_string(i),
                             record.job(std::to_string(i))),
                  FairWorkQueue::Pushed::queued);
    }
    EXPECT_EQ(queue.push(2000, ":x", record.job("x")), FairWorkQueue::Pushed::queue_full);
    gate.release();
    EXPECT_TRUE(wait_until([&] { return record.ran().size() == 4; }));
}

TEST(FairWorkQueue, AJobThatThrowsIsLoggedAndTheWorkerGoesOn) {
    FairWorkQueue queue({1, 8, 256});
    Record record;
    queue.push(1000, ":a", [] { throw std::runtime_error("broken job"); });
    queue.push(1000, ":a", record.job("after"));
    EXPECT_TRUE(wait_until([&] { return record.ran().size() == 1; }));
    EXPECT_TRUE(wait_until([&] { return queue.pending(":a") == 0; }));
}

}  // namespace
}  // namespace vibscore::daemon
