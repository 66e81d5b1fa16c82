#pragma once

#include <chrono>
#include <filesystem>
#include <optional>

// vibscored's virtual vibra (daemon/virtual_vibra) seen from its clients' side, for the hil
// tests and the guest benchmarks.
namespace vibscore::hil {

// Its /dev/input/eventN, found by its phys once vibscored has made it; nothing after `timeout`.
std::optional<std::filesystem::path> find_virtual_vibra(
    std::chrono::milliseconds timeout = std::chrono::seconds(10));

// What udev/61-vibscore-virtual-vibra.rules makes udev store for an event node: the database
// entry <udev_data>/c<major>:<minor> with E:FEEDBACKD_TYPE=vibra, which is how feedbackd finds
// its vibra (the guest has no udevd). Removed with this object.
class FeedbackdVibraMark {
  public:
    explicit FeedbackdVibraMark(const std::filesystem::path& event_node,
                                const std::filesystem::path& udev_data = "/run/udev/data");
    ~FeedbackdVibraMark();
    FeedbackdVibraMark(const FeedbackdVibraMark&) = delete;
    FeedbackdVibraMark& operator=(const FeedbackdVibraMark&) = delete;

  private:
    std::filesystem::path entry_;
};

}  // namespace vibscore::hil
