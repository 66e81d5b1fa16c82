#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <memory>
#include <string_view>

#include "dbus/feedback1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "feedback1-proxy.h"

namespace vibscore::client {

// vibscore-feedback's own interface (org.vibscore.Feedback1: EventScores, AssignScore) on the
// bus `connection` reaches, the one proxy of `vibscore assign` and the editor's "use for ...".
// It holds the connection, so it lives as long as the proxy that uses it. Creating it does not
// call: the first call is what finds out whether vibscore-feedback answers (an sdbus::Error).
class FeedbackLink : public sdbus::ProxyInterfaces<org::vibscore::Feedback1_proxy> {
  public:
    explicit FeedbackLink(std::unique_ptr<sdbus::IConnection> connection)
        : ProxyInterfaces(*connection, dbus::service_name(feedback1::kBusName),
                          dbus::object_path(feedback1::kObjectPath)),
          connection_(std::move(connection)) {
        registerProxy();
    }
    ~FeedbackLink() { unregisterProxy(); }
    FeedbackLink(const FeedbackLink&) = delete;
    FeedbackLink& operator=(const FeedbackLink&) = delete;

  private:
    // Nobody here follows the signal: both users ask again when they need the list.
    void onEventScoresChanged() override {}
    std::unique_ptr<sdbus::IConnection> connection_;
};

static_assert(std::string_view(org::vibscore::Feedback1_proxy::INTERFACE_NAME) ==
              feedback1::kInterface);

}  // namespace vibscore::client
