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

}  // namespace
}  // namespace vibscore::daemon
