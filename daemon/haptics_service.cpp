#include "daemon/haptics_service.hpp"

#include <time.h>

#include <algorithm>
#include <mutex>

#include "actuator/declaration.hpp"
#include "common/log.hpp"
#include "common/monotonic_clock.hpp"
#include "common/number_text.hpp"
#include "config.h"
#include "daemon/bus_errors.hpp"
#include "daemon/calibration_reply.hpp"
#include "daemon/request_error.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/name_owner_watch.hpp"
#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

namespace {

// The CPU time of the calling thread: what a worker's job cost, charged to its caller.
double thread_cpu_s() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) / 1e9;
}

// A request that carries a document needs its CPU budget not overdrawn (admission.hpp: a cost
// above 0 needs the bucket at or above it); its real CPU time is charged once its work has run.
constexpr double kDocumentCpuProbe_s = 1e-9;

Cost document_cost(std::size_t bytes) {
    return {1.0, static_cast<double>(bytes), bytes > 0 ? kDocumentCpuProbe_s : 0.0};
}

// The properties the running backend and the declared actuator decide, read on the playback
// thread, where the host switches and the declaration changes.
void take_from_host(BusProperties& properties, const ActuatorHost& host) {
    properties.driver = host.driver();
    properties.driver_reason = host.reason();
    properties.capabilities = host.capabilities().names();
    properties.actuator.clear();
    if (const auto& declared = host.declaration()) {
        for (auto& [key, value] : actuator::to_settings(*declared)) {
            properties.actuator.emplace(std::move(key), std::move(value));
        }
    }
}

DocumentKind kind_named(const std::string& kind) {
    const auto parsed = parse_document_kind(kind);
    if (!parsed) {
        throw RequestError(RequestError::Code::invalid,
                           "unknown kind \"" + kind + "\" (expected score or clef)");
    }
    return *parsed;
}

}  // namespace

HapticsService::HapticsService(sdbus::IConnection& connection, const DaemonConfig& config,
                               Registry& registry, PlaybackThread& playback,
                               CallerDirectory& callers, ActuatorHost& host, Authorizer& authorizer)
    : AdaptorInterfaces(connection, dbus::object_path(haptics1::kObjectPath)),
      config_(config),
      registry_(registry),
      playback_(playback),
      callers_(callers),
      host_(host),
      authorizer_(authorizer) {
    // The first snapshot; from here on the playback thread publishes each change itself.
    playback_.call([&playback = playback_, &host = host_](Player& player) {
        playback.publish([&](BusProperties& properties) {
            take_from_host(properties, host);
            properties.intensity = player.master_intensity();
        });
    });
    const auto properties = playback_.properties();
    announced_driver_ = properties->driver;
    announced_reason_ = properties->driver_reason;
    announced_capabilities_ = properties->capabilities;
    announced_actuator_ = properties->actuator;
    vanish_watch_ = dbus::watch_connections_leaving(connection, [this](const std::string& name) {
        callers_.forget(name);
        admission_.forget(name);
        authorizer_.forget(name);
        try {
            playback_.call([name](Player& player) { player.sender_vanished(name); });
        } catch (const PlaybackStuck& stuck) {
            log::error("could not end the playbacks of " + name + ": " + stuck.what());
        }
    });
    playback_.set_listener(this);
    // A switch or a new declaration happens on the playback thread, which publishes it; the bus
    // hears of it on the bus thread.
    host_.on_change([this] {
        playback_.publish(
            [&host = host_](BusProperties& properties) { take_from_host(properties, host); });
        playback_.to_bus([this] { driver_switched(); });
    });
    registerAdaptor();
}

HapticsService::~HapticsService() {
    *alive_ = false;
    unregisterAdaptor();
    host_.on_change(nullptr);
    playback_.set_listener(nullptr);
}

// The properties the playback thread owns are read from its last snapshot: no read waits for
// it (bus_properties.hpp).
std::string HapticsService::Driver() {
    return playback_.properties()->driver;
}

std::string HapticsService::DriverReason() {
    return playback_.properties()->driver_reason;
}

std::map<std::string, std::string> HapticsService::RegistryFolders() {
    return {{"shipped", config_.shipped.string()}, {"store", config_.store.string()}};
}

std::vector<std::string> HapticsService::Capabilities() {
    return playback_.properties()->capabilities;
}

std::map<std::string, std::string> HapticsService::Actuator() {
    return playback_.properties()->actuator;
}

double HapticsService::Intensity() {
    return playback_.properties()->intensity;
}

void HapticsService::driver_switched() {
    const auto properties = playback_.properties();
    const auto& driver = properties->driver;
    const auto& reason = properties->driver_reason;
    const auto& capabilities = properties->capabilities;
    const auto& actuator = properties->actuator;
    if (driver == announced_driver_ && reason == announced_reason_ &&
        capabilities == announced_capabilities_ && actuator == announced_actuator_) {
        return;
    }
    announced_driver_ = driver;
    announced_reason_ = reason;
    announced_capabilities_ = capabilities;
    announced_actuator_ = actuator;
    dbus::emit_properties_changed(getObject(), INTERFACE_NAME,
                                  {"Driver", "DriverReason", "Capabilities", "Actuator"});
}

void HapticsService::republish_actuator() {
    try {
        playback_.call([&playback = playback_, &host = host_](Player&) {
            playback.publish(
                [&host](BusProperties& properties) { take_from_host(properties, host); });
        });
    } catch (const PlaybackStuck& stuck) {
        // The snapshot follows at the next switch or reload; the signal still goes out.
        log::error("after a calibration: " + std::string(stuck.what()));
    }
    announced_actuator_ = playback_.properties()->actuator;
}

Caller HapticsService::identify_caller() {
    return dbus::with_current_message(
        getObject(),
        [&](const sdbus::Message& message) -> const Caller& { return callers_.identify(message); });
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

Caller HapticsService::admit_caller(const Cost& cost, ChargedTo* charged_to) {
    const Caller caller = identify_caller();
    // The running configuration's budgets (a reload applies from the next request).
    AdmissionBudgets budgets = config_.admission;
    budgets.user.rate.requests = config_.requests_per_second;
    budgets.user.burst.requests = config_.request_burst;
    admission_.set_budgets(budgets);
    const auto admitted = admission_.admit(caller.uid, caller.sender, cost, monotonic_now_us());
    if (!admitted.admitted) {
        throw RequestError(RequestError::Code::limit_exceeded, admitted.refusal);
    }
    if (charged_to != nullptr) {
        *charged_to = admitted.charged_to;
    }
    return caller;
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

struct HapticsService::PlayWork {
    std::optional<PlaybackRequest> request;
    std::exception_ptr error;
    double cpu_s = 0.0;
};

void HapticsService::Play(sdbus::Result<std::uint64_t>&& result, std::string score,
                          std::map<std::string, sdbus::Variant> options) {
    const auto reply = DeferredReply<std::uint64_t>::make(std::move(result), "Play");
    reply->start([&] {
        ChargedTo charged_to = ChargedTo::nothing;
        const auto bytes = document_bytes(score, options);
        const auto admitted = admit_document(reply, bytes, charged_to);
        if (!admitted) {
            return;
        }
        const Caller& caller = *admitted;
        const PlayOptions play_options = parse_play_options(options);
        auto shared_score = std::make_shared<const std::string>(std::move(score));
        if (!needs_urgent_usage(play_options.usage)) {
            queue_play(reply, caller, charged_to, std::move(shared_score), play_options, bytes > 0);
            return;
        }
        const std::string what = "Playing with usage " + std::string(to_string(play_options.usage));
        authorizer_.decide(caller, Action::urgent_usage,
                           [this, reply, caller, charged_to, shared_score, play_options, what,
                            bytes](const Decision& decision) {
                               reply->start([&] {
                                   decision.require(what);
                                   queue_play(reply, caller, charged_to, shared_score, play_options,
                                              bytes > 0);
                               });
                           });
    });
}

void HapticsService::queue_play(const std::shared_ptr<DeferredReply<std::uint64_t>>& reply,
                                const Caller& caller, ChargedTo charged_to,
                                std::shared_ptr<const std::string> score,
                                const PlayOptions& options, bool carries_document) {
    // A request that would be refused is refused before its score is read or rendered.
    const double cool_down_s = config_.limits.cool_down_s();
    playback_.call([uid = caller.uid, usage = options.usage, repeat = options.repeat,
                    cool_down_s](Player& player) {
        player.check_cool_down(uid, usage, repeat, cool_down_s);
        player.check_admission(usage, repeat);
    });
    // The worker gets a copy of what it needs of the configuration: a reload may replace the
    // running one meanwhile. Fits made for other [clefs] are not kept.
    if (config_.device_clefs != fit_cache_clefs_) {
        fit_cache_.clear();
        fit_cache_clefs_ = config_.device_clefs;
    }
    // With [clefs] fit = auto, binding may fit a clef to the actuator (on a miss of the fit
    // cache, far more work than the rest): that is done on a worker, never the bus thread.
    const bool may_fit = config_.device_clefs.fit_to.has_value() && options.clef.empty();
    if (Admission::exempt(caller.uid) && !carries_document && !may_fit) {
        // Root's and the daemon's own Play of a registry score: nothing of a caller's is parsed
        // (the registry's scores are parsed already), nothing is fitted, its work is bounded by
        // what the registry holds, and it keeps its head-room by not waiting for a worker's
        // turn and two more thread hops.
        auto work =
            prepare_play(*score, options, config_.device_clefs, config_.separation_ms / 1000.0);
        reply->finish([&] {
            if (work->error) {
                std::rethrow_exception(work->error);
            }
            return start_play(caller, std::move(*work->request), options);
        });
        return;
    }
    auto job = [this, alive = alive_, reply, caller, charged_to, score = std::move(score), options,
                device_clefs = config_.device_clefs,
                separation_s = config_.separation_ms / 1000.0]() mutable {
        auto work = prepare_play(*score, options, device_clefs, separation_s);
        score.reset();
        // Back on the bus thread, which alone talks to the bus and the player.
        playback_.to_bus([this, alive = std::move(alive), reply = std::move(reply), caller,
                          charged_to, options, work = std::move(work)] {
            if (!*alive) {
                return;
            }
            admission_.charge_after(caller.uid, caller.sender, charged_to, {0.0, 0.0, work->cpu_s},
                                    monotonic_now_us());
            reply->finish([&] {
                if (work->error) {
                    std::rethrow_exception(work->error);
                }
                return start_play(caller, std::move(*work->request), options);
            });
        });
    };
    auto& lane = Admission::exempt(caller.uid) ? exempt_work_
                 : carries_document            ? document_work_
                                               : registry_work_;
    push_work(lane, caller, std::move(job), "Plays");
}

void HapticsService::push_work(FairWorkQueue& lane, const Caller& caller, std::function<void()> job,
                               const std::string& what) {
    switch (lane.push(caller.uid, caller.sender, std::move(job))) {
        case FairWorkQueue::Pushed::queued:
            return;
        case FairWorkQueue::Pushed::connection_full:
            throw RequestError(RequestError::Code::limit_exceeded,
                               "connection " + caller.sender + " (uid " +
                                   std::to_string(caller.uid) + ") already has " +
                                   std::to_string(lane.options().per_connection) + " " + what +
                                   " waiting for the worker, the most one connection may");
        case FairWorkQueue::Pushed::queue_full:
            throw RequestError(RequestError::Code::limit_exceeded,
                               std::to_string(lane.options().total) + " " + what +
                                   " are waiting for the worker, the most it holds");
    }
}

std::shared_ptr<HapticsService::PlayWork> HapticsService::prepare_play(
    const std::string& score, const PlayOptions& options, const DeviceClefs& device_clefs,
    double separation_s) {
    auto work = std::make_shared<PlayWork>();
    const double cpu_before = thread_cpu_s();
    try {
        std::shared_lock lock(registry_lock_);
        auto found = find_score_to_play(registry_, score, options, device_clefs, &fit_cache_);
        lock.unlock();
        work->request = make_playback_request(found, options, separation_s);
    } catch (...) {
        work->error = std::current_exception();
    }
    work->cpu_s = thread_cpu_s() - cpu_before;
    return work;
}

std::uint64_t HapticsService::start_play(const Caller& caller, PlaybackRequest request,
                                         const PlayOptions& options) {
    request.owner = caller.uid;
    request.sender = caller.sender;
    request.max_on_time_s = config_.limits.max_on_time(options.usage);
    const auto label = request.label;
    // Asked again with the play: the caller's previous playback may have been cut off while
    // this one's score was rendered.
    const double cool_down_s = config_.limits.cool_down_s();
    const auto id =
        playback_.call([uid = caller.uid, usage = options.usage, repeat = options.repeat,
                        cool_down_s, request = std::move(request)](Player& player) mutable {
            player.check_cool_down(uid, usage, repeat, cool_down_s);
            player.check_admission(usage, repeat);
            return player.play(std::move(request));
        });
    log::debug("playback " + std::to_string(id) + ": " + label + " (" +
                   std::string(to_string(options.usage)) + ") for uid " +
                   std::to_string(caller.uid),
               {{"PLAYBACK_ID", std::to_string(id)},
                {"CALLER_UID", std::to_string(caller.uid)},
                {"USAGE", std::string(to_string(options.usage))},
                {"SCORE", label}});
    return id;
}

namespace {

// What a stop's result means to its caller: nothing, or the error it gets.
void answer_stop(Player::StopResult result, std::uint64_t playback_id) {
    switch (result) {
        case Player::StopResult::stopped:
        case Player::StopResult::not_playing:
            return;
        case Player::StopResult::not_found:
            throw RequestError(RequestError::Code::not_found,
                               "no playback " + std::to_string(playback_id) + " was started");
        case Player::StopResult::not_permitted:
            throw RequestError(RequestError::Code::permission_denied,
                               "playback " + std::to_string(playback_id) +
                                   " belongs to another user; stopping it needs "
                                   "org.vibscore.manage");
    }
}

}  // namespace

Player::StopResult HapticsService::stop(const Caller& caller, std::uint64_t playback_id,
                                        bool privileged) {
    return playback_.call([playback_id, uid = caller.uid, privileged](Player& player) {
        return player.stop(playback_id, uid, privileged);
    });
}

void HapticsService::Stop(sdbus::Result<>&& result, std::uint64_t playback_id) {
    const auto reply = DeferredReply<>::make(std::move(result), "Stop");
    reply->start([&] {
        const Caller caller = admit_caller();
        const auto first = stop(caller, playback_id, false);
        // Only a stop that would be refused asks polkit: a caller's own playbacks need no action.
        if (first != Player::StopResult::not_permitted) {
            reply->finish([&] { answer_stop(first, playback_id); });
            return;
        }
        authorizer_.decide(
            caller, Action::manage, [this, reply, caller, playback_id](const Decision& decision) {
                reply->finish([&] {
                    answer_stop(decision.allowed() ? stop(caller, playback_id, true)
                                                   : Player::StopResult::not_permitted,
                                playback_id);
                });
            });
    });
}

void HapticsService::StopAll(sdbus::Result<>&& result) {
    const auto reply = DeferredReply<>::make(std::move(result), "StopAll");
    reply->start([&] {
        const Caller caller = admit_caller();
        when_allowed(
            reply, caller, Action::manage, "Stopping every user's playback", [this, caller] {
                const auto ended =
                    playback_.call([](Player& player) { return player.stop_every_playback(); });
                std::string which;
                for (const auto id : ended) {
                    which += " " + std::to_string(id);
                }
                log::info("uid " + std::to_string(caller.uid) + " stopped every playback:" +
                              (which.empty() ? std::string(" none was playing") : which),
                          {{"CALLER_UID", std::to_string(caller.uid)}, {"REASON", "stop-all"}});
            });
    });
}

void HapticsService::Compose(sdbus::Result<>&& result, std::string name, std::string document) {
    const auto reply = DeferredReply<>::make(std::move(result), "Compose");
    reply->start([&] {
        ChargedTo charged_to = ChargedTo::nothing;
        const auto admitted = admit_document(reply, document.size(), charged_to);
        if (!admitted) {
            return;
        }
        const Caller& caller = *admitted;
        auto shared_document = std::make_shared<const std::string>(std::move(document));
        authorizer_.decide(caller, Action::compose,
                           [this, reply, caller, charged_to, name = std::move(name),
                            shared_document](const Decision& decision) {
                               reply->start([&] {
                                   decision.require("Compose");
                                   queue_compose(reply, caller, charged_to, name, shared_document,
                                                 0);
                               });
                           });
    });
}

// A compose checked this many times, each time overtaken by another change stored before its
// own, is refused (Busy) rather than checked again without end.
constexpr int kComposeAttempts = 4;

void HapticsService::queue_compose(const std::shared_ptr<DeferredReply<>>& reply,
                                   const Caller& caller, ChargedTo charged_to, std::string name,
                                   std::shared_ptr<const std::string> document, int attempt) {
    struct ComposeWork {
        std::optional<Registry::PreparedCompose> prepared;
        std::exception_ptr error;
        double cpu_s = 0.0;
    };
    auto job = [this, alive = alive_, reply, caller, charged_to, name = std::move(name),
                document = std::move(document), attempt]() mutable {
        auto work = std::make_shared<ComposeWork>();
        const double cpu_before = thread_cpu_s();
        try {
            const std::shared_lock lock(registry_lock_);
            work->prepared = registry_.prepare_compose(name, *document);
        } catch (...) {
            work->error = std::current_exception();
        }
        work->cpu_s = thread_cpu_s() - cpu_before;
        // Back on the bus thread, which alone writes the registry and talks to the bus.
        playback_.to_bus([this, alive = std::move(alive), reply = std::move(reply), caller,
                          charged_to, name = std::move(name), document = std::move(document),
                          attempt, work = std::move(work)]() mutable {
            if (!*alive) {
                return;
            }
            admission_.charge_after(caller.uid, caller.sender, charged_to, {0.0, 0.0, work->cpu_s},
                                    monotonic_now_us());
            reply->start([&] {
                if (work->error) {
                    std::rethrow_exception(work->error);
                }
                std::unique_lock lock(registry_lock_);
                const auto stored = registry_.commit_compose(std::move(*work->prepared));
                lock.unlock();
                if (stored) {
                    reply->finish([&] { composed(caller, *stored, name); });
                    return;
                }
                // Another compose or delete was stored since it was checked: what it was
                // checked against may be gone, so it is checked again, on the worker.
                if (attempt + 1 >= kComposeAttempts) {
                    throw RegistryError(RegistryError::Code::in_use,
                                        "the registry changed " + std::to_string(attempt + 1) +
                                            " times while \"" + name +
                                            "\" was being checked; compose it again");
                }
                queue_compose(reply, caller, charged_to, name, document, attempt + 1);
            });
        });
    };
    push_work(Admission::exempt(caller.uid) ? exempt_work_ : document_work_, caller, std::move(job),
              "Composes");
}

void HapticsService::composed(const Caller& caller, DocumentKind kind, const std::string& name) {
    if (kind == DocumentKind::clef) {
        fit_cache_.clear();  // the fits of the clef composed over are stale
    }
    log::info("uid " + std::to_string(caller.uid) + " composed " + std::string(to_string(kind)) +
                  " \"" + name + "\"",
              {{"CALLER_UID", std::to_string(caller.uid)}, {"SCORE", name}});
    if (kind == DocumentKind::clef) {
        log_stored_clef(registry_, config_.device_clefs, config_.actuator, name);
    }
    emitRegistryChanged(std::string(to_string(kind)), name);
}

void HapticsService::Delete(sdbus::Result<>&& result, std::string kind, std::string name) {
    const auto reply = DeferredReply<>::make(std::move(result), "Delete");
    reply->start([&] {
        const Caller caller = admit_caller();
        const auto which = kind_named(kind);
        when_allowed(reply, caller, Action::compose, "Delete", [this, caller, which, name] {
            {
                const std::unique_lock lock(registry_lock_);
                registry_.remove(which, name);
            }
            if (which == DocumentKind::clef) {
                fit_cache_.clear();
            }
            log::info("uid " + std::to_string(caller.uid) + " deleted " +
                          std::string(to_string(which)) + " \"" + name + "\"",
                      {{"CALLER_UID", std::to_string(caller.uid)}, {"SCORE", name}});
            emitRegistryChanged(std::string(to_string(which)), name);
        });
    });
}

std::vector<sdbus::Struct<std::string, std::string>> HapticsService::List(const std::string& kind) {
    return guarded("List", [&] {
        admit_caller();
        std::vector<sdbus::Struct<std::string, std::string>> entries;
        for (const auto& entry : registry_.list(kind_named(kind))) {
            entries.emplace_back(entry.name, entry.title);
        }
        return entries;
    });
}

std::string HapticsService::Get(const std::string& kind, const std::string& name) {
    return guarded("Get", [&] {
        admit_caller();
        return registry_.get(kind_named(kind), name);
    });
}

std::string HapticsService::Origin(const std::string& kind, const std::string& name) {
    return guarded("Origin", [&] {
        admit_caller();
        return std::string(to_string(registry_.origin(kind_named(kind), name)));
    });
}

namespace {

using BarClefList = std::vector<sdbus::Struct<std::string, std::string>>;

BarClefList bar_clef_list(const ScoreBundle& bundle, const DeviceClefs& device_clefs) {
    BarClefList bars;
    for (auto& bar : bar_clefs(bundle, device_clefs)) {
        bars.emplace_back(std::move(bar.written), std::move(bar.device));
    }
    return bars;
}

}  // namespace

void HapticsService::BarClefs(sdbus::Result<BarClefList>&& result, std::string score) {
    const auto reply = DeferredReply<BarClefList>::make(std::move(result), "BarClefs");
    reply->start([&] {
        ChargedTo charged_to = ChargedTo::nothing;
        const auto bytes = document_bytes(score, PlayOptions{});
        const auto admitted = admit_document(reply, bytes, charged_to);
        if (!admitted) {
            return;
        }
        const Caller& caller = *admitted;
        if (bytes == 0) {
            // A registry score's name: its bundle is held, parsed and bound, already.
            reply->finish([&] {
                return bar_clef_list(find_score_to_play(registry_, score, PlayOptions{}).bundle,
                                     config_.device_clefs);
            });
            return;
        }
        // An inline document: parsed and bound on the worker, as Play's.
        struct BarClefsWork {
            BarClefList bars;
            std::exception_ptr error;
            double cpu_s = 0.0;
        };
        auto job = [this, alive = alive_, reply, caller, charged_to,
                    score = std::make_shared<const std::string>(std::move(score)),
                    device_clefs = config_.device_clefs]() mutable {
            auto work = std::make_shared<BarClefsWork>();
            const double cpu_before = thread_cpu_s();
            try {
                std::shared_lock lock(registry_lock_);
                auto found = find_score_to_play(registry_, *score, PlayOptions{});
                lock.unlock();
                work->bars = bar_clef_list(found.bundle, device_clefs);
            } catch (...) {
                work->error = std::current_exception();
            }
            work->cpu_s = thread_cpu_s() - cpu_before;
            score.reset();
            playback_.to_bus([this, alive = std::move(alive), reply = std::move(reply), caller,
                              charged_to, work = std::move(work)] {
                if (!*alive) {
                    return;
                }
                admission_.charge_after(caller.uid, caller.sender, charged_to,
                                        {0.0, 0.0, work->cpu_s}, monotonic_now_us());
                reply->finish([&] {
                    if (work->error) {
                        std::rethrow_exception(work->error);
                    }
                    return std::move(work->bars);
                });
            });
        };
        push_work(Admission::exempt(caller.uid) ? exempt_work_ : document_work_, caller,
                  std::move(job), "BarClefs calls");
    });
}

std::vector<sdbus::Struct<std::string, std::string>> HapticsService::ListDrivers() {
    return guarded("ListDrivers", [&] {
        admit_caller();
        std::vector<sdbus::Struct<std::string, std::string>> drivers;
        for (const auto& driver : host_.drivers()) {
            drivers.emplace_back(driver.name, driver.description);
        }
        return drivers;
    });
}

void HapticsService::SwitchDriver(sdbus::Result<>&& result, std::string driver) {
    const auto reply = DeferredReply<>::make(std::move(result), "SwitchDriver");
    reply->start([&] {
        const Caller caller = admit_caller();
        when_allowed(reply, caller, Action::manage, "Switching the driver", [this, caller, driver] {
            const auto known = host_.drivers();
            if (std::none_of(known.begin(), known.end(), [&](const drivers::DriverInfo& info) {
                    return info.name == driver;
                })) {
                std::string names;
                for (const auto& info : known) {
                    names += (names.empty() ? "" : ", ") + info.name;
                }
                throw RequestError(RequestError::Code::not_found,
                                   "no driver \"" + driver + "\" (available: " + names + ")");
            }
            log::info("uid " + std::to_string(caller.uid) + " switches the driver to " + driver,
                      {{"CALLER_UID", std::to_string(caller.uid)}});
            try {
                playback_.call([&host = host_, driver](Player&) { host.switch_to(driver); });
            } catch (const std::invalid_argument& error) {
                throw RequestError(RequestError::Code::invalid, error.what());
            }
        });
    });
}

void HapticsService::set_intensity(const Caller& caller, double value) {
    if (!(value >= 0.0 && value <= 1.0)) {
        throw RequestError(RequestError::Code::out_of_range,
                           "Intensity " + number_text(value) + " is outside 0..1");
    }
    playback_.call([value, &playback = playback_](Player& player) {
        player.set_master_intensity(value);
        playback.publish([value](BusProperties& properties) { properties.intensity = value; });
    });
    log::info("uid " + std::to_string(caller.uid) + " set Intensity to " + number_text(value),
              {{"CALLER_UID", std::to_string(caller.uid)}});
}

void HapticsService::SetIntensity(sdbus::Result<>&& result, double value) {
    const auto reply = DeferredReply<>::make(std::move(result), "SetIntensity");
    reply->start([&] {
        const Caller caller = admit_caller();
        when_allowed(reply, caller, Action::manage, "Setting Intensity",
                     [this, caller, value] { set_intensity(caller, value); });
    });
}

std::string HapticsService::Version() {
    return VIBSCORE_VERSION;
}

void HapticsService::playback_started(std::uint64_t id, const std::string& label) {
    emitPlaybackStarted(id, label);
    if (calibrator_ != nullptr) {
        calibrator_->playback_started(id);
    }
}

void HapticsService::playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) {
    emitPlaybackPosition(id, static_cast<std::uint32_t>(bar), static_cast<std::uint32_t>(symbol));
}

void HapticsService::playback_finished(std::uint64_t id, const std::string& reason) {
    log::debug("playback " + std::to_string(id) + " finished: " + reason,
               {{"PLAYBACK_ID", std::to_string(id)}, {"REASON", reason}});
    emitPlaybackFinished(id, reason);
    if (calibrator_ != nullptr) {
        calibrator_->playback_finished(id, reason);
    }
}

std::string HapticsService::ActuatorSource() {
    return config_.actuator ? (config_.actuator_source.empty() ? std::string("declared")
                                                               : config_.actuator_source)
                            : std::string();
}

void HapticsService::Calibrate(sdbus::Result<std::map<std::string, sdbus::Variant>>&& result,
                               std::map<std::string, sdbus::Variant> options) {
    const auto reply = DeferredReply<CalibrationReply>::make(std::move(result), "Calibrate");
    reply->start([&] {
        const Caller caller = admit_caller();
        const CalibrateOptions parsed = parse_calibrate_options(options);
        authorizer_.decide(caller, Action::manage,
                           [this, reply, caller, parsed](const Decision& decision) {
                               reply->start([&] {
                                   decision.require("Calibrating the actuator");
                                   start_calibration(reply, caller, parsed);
                               });
                           });
    });
}

void HapticsService::start_calibration(
    const std::shared_ptr<DeferredReply<CalibrationReply>>& reply, const Caller& caller,
    const CalibrateOptions& options) {
    if (calibrator_ == nullptr) {
        throw RequestError(RequestError::Code::invalid, "this daemon cannot calibrate");
    }
    log::info("uid " + std::to_string(caller.uid) + " calibrates the actuator" +
                  (options.apply ? " (apply)" : ""),
              {{"CALLER_UID", std::to_string(caller.uid)}});
    try {
        calibrator_->start(options.apply, caller.uid, caller.sender,
                           [this, reply, options](std::optional<CalibrationOutcome> outcome,
                                                  std::exception_ptr error) {
                               if (outcome && outcome->applied) {
                                   // The numbers in use changed: compensation and clef fitting use
                                   // them now, and the Actuator property says so.
                                   republish_actuator();
                                   dbus::emit_properties_changed(getObject(), INTERFACE_NAME,
                                                                 {"Actuator", "ActuatorSource"});
                               }
                               reply->finish([&] {
                                   if (error) {
                                       throw_calibration_error(error);
                                   }
                                   return calibration_reply(*outcome, options.recording);
                               });
                           });
    } catch (...) {
        throw_calibration_error(std::current_exception());
    }
}

}  // namespace vibscore::daemon
