#pragma once

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "daemon/authority.hpp"

namespace vibscore::testing {

// polkit as the daemon sees it through the PolkitAuthority seam: an answer per action (by
// default not_authorized), or a failure, and every question asked, as (sender, action id).
// It answers at once, or, with `hold` set, only when the test calls answer_held(): a polkit
// that takes its time.
class FakePolkitAuthority : public daemon::PolkitAuthority {
  public:
    void check(const std::string& sender, std::string_view action_id, Answered answered) override {
        asked.emplace_back(sender, std::string(action_id));
        if (hold) {
            held_.emplace_back(std::string(action_id), std::move(answered));
            return;
        }
        answer(std::string(action_id), answered);
    }

    // Answers every held question, in the order asked, as the answers now say.
    void answer_held() {
        auto held = std::move(held_);
        held_.clear();
        for (auto& [action_id, answered] : held) {
            answer(action_id, answered);
        }
    }
    std::size_t held() const { return held_.size(); }

    bool on_the_bus = true;
    bool hold = false;
    std::string failure;  // not empty: polkit fails with it
    std::map<std::string, daemon::PolkitAnswer> answers;
    std::vector<std::pair<std::string, std::string>> asked;

  private:
    void answer(const std::string& action_id, const Answered& answered) const {
        if (!failure.empty()) {
            answered(daemon::PolkitAnswer::failed, failure);
        } else if (!on_the_bus) {
            answered(daemon::PolkitAnswer::unavailable, {});
        } else {
            const auto found = answers.find(action_id);
            answered(found == answers.end() ? daemon::PolkitAnswer::not_authorized : found->second,
                     {});
        }
    }

    std::vector<std::pair<std::string, Answered>> held_;
};

}  // namespace vibscore::testing
