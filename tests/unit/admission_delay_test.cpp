// Refusals answered late (admission by work): a task is posted when it is due, never before,
// and a key has at most one task waiting.
#include "daemon/admission_delay.hpp"

#include <gtest/gtest.h>

#include <mutex>
#include <vector>

#include "tests/support/wait_until.hpp"

namespace vibscore::daemon {
namespace {

using testing::wait_until;
using namespace std::chrono_literals;

// What was posted, as the bus thread's queue would receive it.
class Posted {
  public:
    std::function<void(std::function<void()>)> post() {
        return [this](std::function<void()> task) {
            task();
            const std::lock_guard lock(mutex_);
            ++count_;
        };
    }
    int count() {
        const std::lock_guard lock(mutex_);
        return count_;
    }

  private:
    std::mutex mutex_;
    int count_ = 0;
};

TEST(DelayedTasks, ATaskDueIsPostedAndOneNotYetDueWaits) {
    Posted posted;
    DelayedTasks tasks(posted.post());
    EXPECT_TRUE(tasks.add(":1.1", DelayedTasks::Clock::now() + 1h, [] {}));
    EXPECT_TRUE(tasks.add(":1.2", DelayedTasks::Clock::now(), [] {}));
    EXPECT_TRUE(wait_until([&] { return posted.count() == 1; }));
    EXPECT_EQ(tasks.waiting(), 1u);  // the one due in an hour
}

TEST(DelayedTasks, AKeyHasOneTaskWaitingAndMayAddAgainOnceItWasPosted) {
    Posted posted;
    DelayedTasks tasks(posted.post());
    const auto later = DelayedTasks::Clock::now() + 1h;
    EXPECT_TRUE(tasks.add(":1.1", later, [] {}));
    EXPECT_FALSE(tasks.add(":1.1", later, [] {}));  // the second refusal is answered at once
    EXPECT_TRUE(tasks.add(":1.2", DelayedTasks::Clock::now(), [] {}));
    ASSERT_TRUE(wait_until([&] { return posted.count() == 1; }));
    EXPECT_TRUE(tasks.add(":1.2", DelayedTasks::Clock::now(), [] {}));
    EXPECT_TRUE(wait_until([&] { return posted.count() == 2; }));
}

TEST(DelayedTasks, TasksArePostedInTheOrderTheyAreDue) {
    std::mutex mutex;
    std::vector<int> order;
    DelayedTasks tasks([&](std::function<void()> task) { task(); });
    const auto now = DelayedTasks::Clock::now();
    const auto record = [&](int which) {
        return [&, which] {
            const std::lock_guard lock(mutex);
            order.push_back(which);
        };
    };
    tasks.add("c", now + 30ms, record(3));
    tasks.add("a", now + 10ms, record(1));
    tasks.add("b", now + 20ms, record(2));
    ASSERT_TRUE(wait_until([&] {
        const std::lock_guard lock(mutex);
        return order.size() == 3;
    }));
    EXPECT_EQ(order, (std::vector<int>{1, 2, 3}));
}

// A user's refusals a delay after each and a spacing apart, whatever its connections: the
// edges are the delay itself, the spacing exactly, and a pause long enough to start afresh.
TEST(RefusalPacing, AUsersRefusalsComeADelayLaterAndASpacingApart) {
    RefusalPacing pacing(1000ms, 500ms);
    const RefusalPacing::Clock::time_point t0{};
    EXPECT_EQ(pacing.due(1000, t0), t0 + 1000ms);
    // Twenty connections refused in the same instant: one every 500 ms from the first.
    for (int i = 1; i < 20; ++i) {
        EXPECT_EQ(pacing.due(1000, t0), t0 + 1000ms + i * 500ms) << i;
    }
    // Another user is paced on its own.
    EXPECT_EQ(pacing.due(1001, t0), t0 + 1000ms);
}

TEST(RefusalPacing, AfterAPauseTheNextRefusalIsOnlyADelayLater) {
    RefusalPacing pacing(1000ms, 500ms);
    const RefusalPacing::Clock::time_point t0{};
    EXPECT_EQ(pacing.due(1000, t0), t0 + 1000ms);  // the next may come at 1500 ms
    // Refused at 499 ms: 1499 ms would be 1 ms too close to the first, so 1500 ms.
    EXPECT_EQ(pacing.due(1000, t0 + 499ms), t0 + 1500ms);
    // Refused at 1001 ms (next allowed 2000 ms): a delay later is 2001 ms, past the spacing.
    EXPECT_EQ(pacing.due(1000, t0 + 1001ms), t0 + 2001ms);
}

TEST(RefusalPacing, UsersWhosePacingRanOutAreForgottenOnceThereAreMany) {
    RefusalPacing pacing(1000ms, 500ms);
    const RefusalPacing::Clock::time_point t0{};
    for (uid_t uid = 1; uid <= 65; ++uid) {
        pacing.due(uid, t0);
    }
    EXPECT_EQ(pacing.users(), 65u);
    pacing.due(2000, t0 + 1500ms);  // every earlier user's next was due by 1500 ms
    EXPECT_EQ(pacing.users(), 1u);
}

}  // namespace
}  // namespace vibscore::daemon
