#pragma once

// The admission steps HapticsService's methods share across its files (haptics_service*.cpp):
// templates on the reply type, so defined where each file that uses them can see them.
#include <memory>
#include <optional>
#include <string>

#include "daemon/haptics_service.hpp"
#include "daemon/request_error.hpp"

namespace vibscore::daemon {

// A request that carries a document needs its CPU budget not overdrawn (admission.hpp: a cost
// above 0 needs the bucket at or above it); its real CPU time is charged once its work has run.
constexpr double kDocumentCpuProbe_s = 1e-9;

inline Cost document_cost(std::size_t bytes) {
    return {1.0, static_cast<double>(bytes), bytes > 0 ? kDocumentCpuProbe_s : 0.0};
}

// Each refusal waiting holds its request's message (up to a megabyte): at most this many wait,
// the next are answered at once.
constexpr std::size_t kMostRefusalsWaiting = 32;

template <typename Reply>
void HapticsService::refuse_later(const std::shared_ptr<Reply>& reply, const Caller& caller,
                                  const RequestError& refusal) {
    const bool queued =
        refusals_.waiting() < kMostRefusalsWaiting &&
        refusals_.add(caller.sender, refusal_pacing_.due(caller.uid, DelayedTasks::Clock::now()),
                      [reply, alive = alive_, message = std::string(refusal.what())] {
                          if (*alive) {
                              reply->fail(std::make_exception_ptr(
                                  RequestError(RequestError::Code::limit_exceeded, message)));
                          }
                      });
    if (!queued) {
        throw refusal;
    }
}

template <typename Reply>
std::optional<Caller> HapticsService::admit_document(const std::shared_ptr<Reply>& reply,
                                                     std::size_t bytes, ChargedTo& charged_to) {
    try {
        return admit_caller(document_cost(bytes), &charged_to);
    } catch (const RequestError& refusal) {
        if (bytes == 0 || refusal.code() != RequestError::Code::limit_exceeded) {
            throw;
        }
        refuse_later(reply, identify_caller(), refusal);
        return std::nullopt;
    }
}

template <typename Reply, typename Then>
void HapticsService::when_allowed(const std::shared_ptr<Reply>& reply, const Caller& caller,
                                  std::optional<Action> action, std::string what, Then then) {
    if (!action) {
        reply->finish(then);
        return;
    }
    authorizer_.decide(
        caller, *action,
        [reply, what = std::move(what), then = std::move(then)](const Decision& decision) mutable {
            reply->finish([&] {
                decision.require(what);
                return then();
            });
        });
}

}  // namespace vibscore::daemon
