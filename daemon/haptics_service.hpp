#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <map>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <string>
#include <vector>

#include "daemon/actuator_host.hpp"
#include "daemon/admission.hpp"
#include "daemon/admission_delay.hpp"
#include "daemon/authority.hpp"
#include "daemon/calibration_reply.hpp"
#include "daemon/calibrator.hpp"
#include "daemon/callers.hpp"
#include "daemon/clef_fit_cache.hpp"
#include "daemon/config.hpp"
#include "daemon/deferred_reply.hpp"
#include "daemon/play_request.hpp"
#include "daemon/playback_thread.hpp"
#include "daemon/registry/registry.hpp"
#include "daemon/request_error.hpp"
#include "daemon/work_queue.hpp"
#include "haptics1-adaptor.h"

namespace vibscore::daemon {

// The org.vibscore.Haptics1 object: the bus adaptor, on the bus thread. It finds out who calls
// and admits them, then hands the work to the registry, play_request, and (on the playback
// thread) the player and the actuator host, and turns what they report into signals. Every
// failure leaves as a named D-Bus error (bus_errors.hpp); nothing a caller sends can stop the
// daemon. Methods that may need polkit's answer reply when it comes (DeferredReply), so the bus
// thread never waits for one caller's authorization while others call. Every method is admitted
// by work (admission.hpp): its cost is charged to its connection's and its user's budgets before
// anything is read. Play's document work (parsing, binding, fitting, rendering) runs on a fair
// worker (work_queue.hpp), never on the bus thread; its result comes back to the bus thread,
// which starts the playback and replies.
class HapticsService final : public sdbus::AdaptorInterfaces<org::vibscore::Haptics1_adaptor>,
                             public PlayerListener {
  public:
    // `config` is the running configuration (a reload replaces its contents). The service
    // listens to the player and the host, and watches callers leave the bus, until destroyed.
    HapticsService(sdbus::IConnection& connection, const DaemonConfig& config, Registry& registry,
                   PlaybackThread& playback, CallerDirectory& callers, ActuatorHost& host,
                   Authorizer& authorizer);
    ~HapticsService() override;

    // Who runs Calibrate (none: Calibrate is refused); set once, before the bus is served.
    void set_calibrator(Calibrator* calibrator) { calibrator_ = calibrator; }

    // PlayerListener: playback events become signals.
    void playback_started(std::uint64_t id, const std::string& label) override;
    void playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) override;
    void playback_finished(std::uint64_t id, const std::string& reason) override;

  private:
    void Play(sdbus::Result<std::uint64_t>&& result, std::string score,
              std::map<std::string, sdbus::Variant> options) override;
    void Stop(sdbus::Result<>&& result, std::uint64_t playback_id) override;
    void StopAll(sdbus::Result<>&& result) override;
    void Compose(sdbus::Result<>&& result, std::string name, std::string document) override;
    void Delete(sdbus::Result<>&& result, std::string kind, std::string name) override;
    std::vector<sdbus::Struct<std::string, std::string>> List(const std::string& kind) override;
    std::string Get(const std::string& kind, const std::string& name) override;
    std::string Origin(const std::string& kind, const std::string& name) override;
    void BarClefs(sdbus::Result<std::vector<sdbus::Struct<std::string, std::string>>>&& result,
                  std::string score) override;
    std::vector<sdbus::Struct<std::string, std::string>> ListDrivers() override;
    void SwitchDriver(sdbus::Result<>&& result, std::string driver) override;
    void SetIntensity(sdbus::Result<>&& result, double value) override;
    void Calibrate(sdbus::Result<std::map<std::string, sdbus::Variant>>&& result,
                   std::map<std::string, sdbus::Variant> options) override;
    std::string ActuatorSource() override;
    std::string Driver() override;
    std::string DriverReason() override;
    std::map<std::string, std::string> RegistryFolders() override;
    std::vector<std::string> Capabilities() override;
    std::map<std::string, std::string> Actuator() override;
    // Read-only: SetIntensity sets it, as only a method can wait for polkit's answer.
    double Intensity() override;
    std::string Version() override;

    // The caller of the method being handled, admitted with `cost` (one request by default);
    // throws RequestError (limit_exceeded) naming the budget it is over. `charged_to`: where the
    // cost went, to charge the work's CPU time to the same.
    Caller admit_caller(const Cost& cost = {1.0, 0.0, 0.0}, ChargedTo* charged_to = nullptr);
    // The caller of the method being handled, not yet admitted.
    Caller identify_caller();
    // What a request carrying `bytes` of a document costs at admission: one request, its bytes,
    // and (when it carries any) a CPU probe, so it needs its CPU budget not overdrawn; its real
    // CPU time is charged once its work has run.
    static Cost document_cost(std::size_t bytes);
    // Each refusal waiting holds its request's message (up to a megabyte): at most this many
    // wait, the next are answered at once.
    static constexpr std::size_t kMostRefusalsWaiting = 32;
    // Refuses a request that carried a document (admission.hpp) through `reply` about a second
    // later (admission_delay.hpp), or at once when its connection already has one waiting.
    template <typename Reply>
    void refuse_later(const std::shared_ptr<Reply>& reply, const Caller& caller,
                      const RequestError& refusal);
    // The caller of a method carrying `bytes` of a document, admitted for them (charged before
    // anything is read: the bytes are counted, not parsed). Nothing when it is over its budget
    // and the refusal goes through `reply` later (refuse_later); a refusal of a request
    // without a document, or of another kind, is thrown at once.
    template <typename Reply>
    std::optional<Caller> admit_document(const std::shared_ptr<Reply>& reply, std::size_t bytes,
                                         ChargedTo& charged_to);
    // Runs `then` under `reply` once `caller` may do `action` (at once when no action is needed
    // or the answer is known; when polkit answers otherwise); a refusal is the reply instead.
    // `then` runs later, so it owns what it uses.
    template <typename Reply, typename Then>
    void when_allowed(const std::shared_ptr<Reply>& reply, const Caller& caller,
                      std::optional<Action> action, std::string what, Then then);

    // What Play's worker hands back to the bus thread.
    struct PlayWork;
    // Refuses what the player would refuse (cool-down, arbitration) before any document work,
    // then queues that work for the worker, which replies through `reply` when it is done.
    // `carries_document`: an inline score or clefs sent along (the caller's document, parsed on
    // the worker for documents), else a registry score's name (the worker for those).
    void queue_play(const std::shared_ptr<DeferredReply<std::uint64_t>>& reply,
                    const Caller& caller, ChargedTo charged_to,
                    std::shared_ptr<const std::string> score, const PlayOptions& options,
                    bool carries_document);
    // On the worker: the score found, bound, fitted and rendered into a request.
    std::shared_ptr<PlayWork> prepare_play(const std::string& score, const PlayOptions& options,
                                           const DeviceClefs& device_clefs, double separation_s);
    // Queues `job` on `lane` for `caller`, or throws RequestError (limit_exceeded) naming the
    // bound that refused it; `what`: the requests it holds ("Plays", "Composes").
    static void push_work(FairWorkQueue& lane, const Caller& caller, std::function<void()> job,
                          const std::string& what);
    // Compose after polkit's answer: the document parsed and validated against the registry on
    // a worker (Registry::prepare_compose, under the reader's lock), stored on the bus thread,
    // which alone writes the registry (commit_compose); checked again on the worker when another
    // compose or delete was stored in between (`attempt`: how many times it was).
    void queue_compose(const std::shared_ptr<DeferredReply<>>& reply, const Caller& caller,
                       ChargedTo charged_to, std::string name,
                       std::shared_ptr<const std::string> document, int attempt);
    // A compose stored: logged, the fits of a clef composed over dropped, RegistryChanged sent.
    void composed(const Caller& caller, DocumentKind kind, const std::string& name);
    // On the bus thread again: the request handed to the player.
    std::uint64_t start_play(const Caller& caller, PlaybackRequest request,
                             const PlayOptions& options);
    Player::StopResult stop(const Caller& caller, std::uint64_t playback_id, bool privileged);
    void set_intensity(const Caller& caller, double value);
    void start_calibration(const std::shared_ptr<DeferredReply<CalibrationReply>>& reply,
                           const Caller& caller, const CalibrateOptions& options);
    // Driver, DriverReason, Capabilities or Actuator changed with a switch or reload: announced
    // with PropertiesChanged.
    void driver_switched();
    // A calibration applied changed the declaration in use: the playback thread publishes it.
    void republish_actuator();

    const DaemonConfig& config_;
    Registry& registry_;
    PlaybackThread& playback_;
    CallerDirectory& callers_;
    ActuatorHost& host_;
    Authorizer& authorizer_;
    std::string announced_driver_;
    std::string announced_reason_;
    std::vector<std::string> announced_capabilities_;
    std::map<std::string, std::string> announced_actuator_;
    sdbus::Slot vanish_watch_;  // NameOwnerChanged: a caller left the bus
    Calibrator* calibrator_ = nullptr;

    Admission admission_;  // the bus thread's
    // Compose's commit and Delete (bus thread) change the registry; the workers read it (and
    // Compose's validation runs there, as a reader).
    std::shared_mutex registry_lock_;
    ClefFitCache fit_cache_;
    DeviceClefs fit_cache_clefs_;  // the [clefs] the cache was filled for: another empties it
    // False once the service is gone: a worker's result that comes back later is dropped.
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
    DelayedTasks refusals_{
        [this](std::function<void()> task) { playback_.to_bus(std::move(task)); }};
    // A refused document is answered a second later, and a user's refusals half a second apart:
    // at most two a second re-sent by a user, however many connections it opens (bus thread).
    RefusalPacing refusal_pacing_{std::chrono::seconds(1), std::chrono::milliseconds(500)};
    // Last, so they are stopped before anything their jobs use: root's and the daemon's own
    // work on a lane of their own (their head-room); everyone else's on two fair ones, so that
    // a Play of a registry score (no caller's document: its work is bounded by what the registry
    // holds) never waits behind the parse of someone's megabyte.
    FairWorkQueue exempt_work_{FairWorkQueue::Options{1, 64, 256}};
    FairWorkQueue registry_work_{FairWorkQueue::Options{}};
    FairWorkQueue document_work_{FairWorkQueue::Options{}};
};

// The admission steps are templates on the reply type: defined here, for each file of the
// service's methods (haptics_service*.cpp) that uses them.

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
