#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <exception>
#include <memory>
#include <utility>

#include "daemon/bus_errors.hpp"

namespace vibscore::daemon {

namespace detail {
// The type a method's body returns: its one result, or void.
template <typename... Results>
struct BodyResult {
    using type = void;
};
template <typename Result>
struct BodyResult<Result> {
    using type = Result;
};
}  // namespace detail

// One method call's reply, kept until its answer is known: for the methods that wait for polkit
// without holding the bus thread (the generated adaptor hands them a sdbus::Result). Exactly one
// reply goes out: finish() sends what its body returns, or the named D-Bus error for what it
// throws (bus_errors.hpp). Shared, so that a callback can keep it alive.
template <typename... Results>
class DeferredReply : public std::enable_shared_from_this<DeferredReply<Results...>> {
  public:
    static std::shared_ptr<DeferredReply> make(sdbus::Result<Results...>&& result,
                                               const char* method) {
        return std::shared_ptr<DeferredReply>(new DeferredReply(std::move(result), method));
    }

    // Runs `body` and replies with its value (nothing for a method without results).
    template <typename Body>
    void finish(Body&& body) {
        if (sent_) {
            return;
        }
        sent_ = true;
        try {
            if constexpr (sizeof...(Results) == 0) {
                guarded(method_, std::forward<Body>(body));
                result_.returnResults();
            } else {
                result_.returnResults(guarded(method_, std::forward<Body>(body)));
            }
        } catch (const sdbus::Error& error) {
            result_.returnError(error);
        }
    }

    // Replies with the named D-Bus error for `error` (bus_errors.hpp).
    void fail(std::exception_ptr error) {
        finish([&]() ->
               typename detail::BodyResult<Results...>::type { std::rethrow_exception(error); });
    }

    // Runs `body`, which arranges for finish() to be called (now or later); what it throws is
    // the reply.
    template <typename Body>
    void start(Body&& body) {
        try {
            guarded(method_, std::forward<Body>(body));
        } catch (const sdbus::Error& error) {
            if (!sent_) {
                sent_ = true;
                result_.returnError(error);
            }
        }
    }

  private:
    DeferredReply(sdbus::Result<Results...>&& result, const char* method)
        : result_(std::move(result)), method_(method) {}

    sdbus::Result<Results...> result_;
    const char* method_;
    bool sent_ = false;
};

}  // namespace vibscore::daemon
