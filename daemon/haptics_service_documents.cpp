#include "daemon/haptics_service.hpp"

#include "common/log.hpp"
#include "daemon/bus_errors.hpp"
#include "daemon/request_error.hpp"
#include "daemon/thread_cpu_time.hpp"
#include "dbus/haptics1_names.hpp"

// HapticsService's registry methods: Compose (checked on a worker, stored in order), Delete,
// List, Get, Origin, and BarClefs.
namespace vibscore::daemon {

namespace {

DocumentKind kind_named(const std::string& kind) {
    const auto parsed = parse_document_kind(kind);
    if (!parsed) {
        throw RequestError(RequestError::Code::invalid,
                           "unknown kind \"" + kind + "\" (expected score or clef)");
    }
    return *parsed;
}

}  // namespace

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

}  // namespace vibscore::daemon
