#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "daemon/authority.hpp"

namespace vibscore::testing {

// polkit as the daemon sees it through the PolkitAuthority seam: an answer per action (by
// default not_authorized), or a failure, and every question asked, as (sender, action id).
class FakePolkitAuthority : public daemon::PolkitAuthority {
  public:
    daemon::PolkitAnswer check(const std::string& sender, std::string_view action_id) override {
        asked.emplace_back(sender, std::string(action_id));
        if (!failure.empty()) {
            throw std::runtime_error(failure);
        }
        if (!on_the_bus) {
            return daemon::PolkitAnswer::unavailable;
        }
        const auto found = answers.find(std::string(action_id));
        return found == answers.end() ? daemon::PolkitAnswer::not_authorized : found->second;
    }

    bool on_the_bus = true;
    std::string failure;  // not empty: check() throws it
    std::map<std::string, daemon::PolkitAnswer> answers;
    std::vector<std::pair<std::string, std::string>> asked;
};

}  // namespace vibscore::testing
