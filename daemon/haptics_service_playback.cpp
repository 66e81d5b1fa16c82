#include "daemon/haptics_service.hpp"

#include "common/log.hpp"
#include "daemon/bus_errors.hpp"
#include "daemon/request_error.hpp"
#include "daemon/thread_cpu_time.hpp"
#include "dbus/haptics1_names.hpp"

// HapticsService's playback methods: Play (its document read on a worker, then started on the
// playback thread), Stop and StopAll.
namespace vibscore::daemon {

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

}  // namespace vibscore::daemon
