#include "client/bus_verbs.hpp"

#include <sdbus-c++/sdbus-c++.h>

#include <pugixml.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "client/clef_verbs.hpp"
#include "client/editor/daemon_errors.hpp"
#include "client/editor/daemon_watch.hpp"
#include "client/editor/documents.hpp"
#include "client/offline_verbs.hpp"
#include "common/number_text.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "haptics1-proxy.h"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"
#include "score/score_xml.hpp"

namespace vibscore::client {

namespace {

std::atomic<bool> g_interrupted{false};

// A client of the daemon that remembers how each playback ended and where each one is.
class Haptics : public sdbus::ProxyInterfaces<org::vibscore::Haptics1_proxy> {
  public:
    explicit Haptics(std::unique_ptr<sdbus::IConnection> connection)
        : ProxyInterfaces(*connection, dbus::service_name(haptics1::kBusName),
                          dbus::object_path(haptics1::kObjectPath)),
          connection_(std::move(connection)) {
        registerProxy();
    }
    ~Haptics() {
        connection_->leaveEventLoop();
        unregisterProxy();
    }
    void listen() { connection_->enterEventLoopAsync(); }
    // Handles the signals that came in before the last call's reply, in this thread: the daemon
    // sends a playback's end before it answers the Stop that ended it.
    void take_signals() {
        while (dbus::process_pending(*connection_)) {
        }
    }
    bool any_stopped() {
        std::lock_guard lock(mutex_);
        return std::any_of(finished_.begin(), finished_.end(),
                           [](const auto& entry) { return entry.second == "stopped"; });
    }
    sdbus::IConnection& connection() { return *connection_; }

    std::optional<std::string> finished(std::uint64_t id) {
        std::lock_guard lock(mutex_);
        const auto found = finished_.find(id);
        return found == finished_.end() ? std::nullopt : std::optional(found->second);
    }
    std::optional<std::pair<std::uint32_t, std::uint32_t>> position(std::uint64_t id) {
        std::lock_guard lock(mutex_);
        const auto found = positions_.find(id);
        return found == positions_.end() ? std::nullopt : std::optional(found->second);
    }

  private:
    void onPlaybackStarted(const uint64_t&, const std::string&) override {}
    void onPlaybackPosition(const uint64_t& id, const uint32_t& bar,
                            const uint32_t& symbol) override {
        std::lock_guard lock(mutex_);
        positions_[id] = {bar, symbol};
    }
    void onPlaybackFinished(const uint64_t& id, const std::string& reason) override {
        std::lock_guard lock(mutex_);
        finished_[id] = reason;
    }
    void onRegistryChanged(const std::string&, const std::string&) override {}

    std::unique_ptr<sdbus::IConnection> connection_;
    std::mutex mutex_;
    std::map<std::uint64_t, std::string> finished_;
    std::map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> positions_;
};

std::string explain(const sdbus::Error& error) {
    return describe_daemon_error(error.getName(), error.getMessage());
}

// The declaration the Actuator property holds: [actuator]'s own keys and values.
actuator::Declaration declaration_of(const std::map<std::string, std::string>& settings) {
    try {
        return actuator::from_settings(settings, "vibscored's Actuator property");
    } catch (const actuator::DeclarationError& error) {
        throw std::runtime_error(error.what());
    }
}

std::string actuator_line(const std::map<std::string, std::string>& settings) {
    if (settings.empty()) {
        return "none declared: strengths play as written ([actuator] in vibscored.conf, "
               "docs/drivers.md)";
    }
    return actuator::describe(declaration_of(settings));
}

// Where the numbers in use come from (ActuatorSource): "declared", or "measured DATE" after
// `vibscore calibrate --apply`; nothing to say when none is declared.
template <typename Proxy>
std::string actuator_source_line(Proxy& haptics) {
    const std::string source = haptics.ActuatorSource();
    return source.empty() ? std::string() : "actuator numbers: " + source + "\n";
}

template <typename Body>
int with_daemon(std::ostream& err, Body&& body) {
    std::unique_ptr<sdbus::IConnection> connection;
    try {
        connection = sdbus::createSystemBusConnection();
    } catch (const sdbus::Error& error) {
        err << "vibscore: cannot connect to the system bus: " << error.getMessage() << "\n";
        return exit_failed;
    }
    try {
        Haptics haptics(std::move(connection));
        return body(haptics);
    } catch (const sdbus::Error& error) {
        err << "vibscore: " << explain(error) << "\n";
    } catch (const DocumentError& error) {
        err << error.what() << "\n";
    } catch (const std::runtime_error& error) {
        err << "vibscore: " << error.what() << "\n";
    }
    return exit_failed;
}

// What Play sends for its SCORE argument: a registry name as it is; a score file, checked by
// the same rule as `check`, as its text with the clef files it names (registry clefs go by name).
struct PlayArgument {
    std::string score;
    std::map<std::string, std::string> clef_documents;  // by href
};

PlayArgument play_argument(const std::string& argument, const ClefSearch& clefs) {
    if (editor::classify_source(argument).kind == editor::ScoreSource::Kind::registry) {
        return {argument, {}};
    }
    const auto loaded = load_score(argument, clefs);
    PlayArgument sent{read_document_file(argument), {}};
    for (const auto& declaration : loaded.bundle.score.clefs) {
        const auto& origin = loaded.clef_origins.at(declaration.id);
        if (origin != kRegistryOrigin) {
            sent.clef_documents[declaration.href] = read_document_file(origin);
        }
    }
    return sent;
}

// A score file as the registry stores it: every clef a registry clef, named by name. A clef found
// as a file is renamed to the registry clef of its file name when that clef is the same.
std::string document_to_compose(Haptics& haptics, const std::string& file,
                                const ClefSearch& clefs) {
    const auto text = read_document_file(file);
    if (document_kind(text, file) == DocumentKind::clef) {
        return text;
    }
    const auto loaded = load_score(file, clefs);
    std::map<std::string, std::string> renamed;  // href -> NAME.clef.xml
    for (const auto& declaration : loaded.bundle.score.clefs) {
        const auto& origin = loaded.clef_origins.at(declaration.id);
        if (origin == kRegistryOrigin) {
            continue;
        }
        const std::string where = "clef \"" + declaration.id + "\" (" + origin + ")";
        const auto name =
            clef_name_in_href(std::filesystem::path(declaration.href).filename().string());
        if (!name) {
            throw std::runtime_error(where +
                                     ": its file name names no registry clef; store the "
                                     "clef first (vibscore compose NAME " +
                                     origin + ") and name it NAME.clef.xml");
        }
        std::optional<Clef> stored;
        try {
            stored = read_clef(haptics.Get("clef", *name), "registry clef \"" + *name + "\"");
        } catch (const sdbus::Error& error) {
            if (error.getName() != haptics1::errors::kNotFound) {
                throw;
            }
        }
        if (!stored) {
            throw std::runtime_error(where + ": the registry has no clef \"" + *name +
                                     "\"; store it first: vibscore compose " + *name + " " +
                                     origin);
        }
        if (!(*stored == loaded.bundle.clefs.at(declaration.id))) {
            throw std::runtime_error(where + " differs from registry clef \"" + *name +
                                     "\"; store it under its own name first (vibscore compose "
                                     "NAME " +
                                     origin + ") and name that in the score");
        }
        renamed[declaration.href] = *name + std::string(kClefSuffix);
    }
    if (renamed.empty()) {
        return text;
    }
    pugi::xml_document document;
    document.load_buffer(text.data(), text.size(), pugi::parse_full);
    for (auto clef : document.document_element().children("Clef")) {
        if (const auto found = renamed.find(clef.attribute("href").value());
            found != renamed.end()) {
            clef.attribute("href").set_value(found->second.c_str());
        }
    }
    std::ostringstream rewritten;
    document.save(rewritten, "", pugi::format_raw | pugi::format_no_declaration);
    return rewritten.str();
}

}  // namespace

int play(const PlayRequest& request, const ClefSearch& clefs, std::ostream& out,
         std::ostream& err) {
    // A file is read and checked before the bus is reached: a missing or invalid file reads the
    // same as in `show` and `check`, whether the daemon runs or not.
    PlayArgument argument;
    try {
        argument = play_argument(request.score, clefs);
    } catch (const DocumentError& error) {
        err << error.what() << "\n";
        return exit_failed;
    } catch (const std::runtime_error& error) {
        err << "vibscore: " << error.what() << "\n";
        return exit_failed;
    }
    return with_daemon(err, [&](Haptics& haptics) {
        std::map<std::string, sdbus::Variant> options;
        if (!argument.clef_documents.empty())
            options["clefs"] = sdbus::Variant(argument.clef_documents);
        if (!request.usage.empty())
            options["usage"] = sdbus::Variant(request.usage);
        if (request.repeat != 0)
            options["repeat"] = sdbus::Variant(std::int32_t{request.repeat});
        if (!request.clef.empty())
            options["clef"] = sdbus::Variant(request.clef);
        if (request.intensity >= 0.0)
            options["intensity"] = sdbus::Variant(request.intensity);
        std::optional<DaemonWatch> watch;
        if (request.wait) {
            watch.emplace(haptics.connection());
            haptics.listen();
        }
        const auto id = haptics.Play(argument.score, options);
        if (!request.wait) {
            out << id << "\n";
            return exit_ok;
        }
        watch->follow();
        // Ctrl-C stops the playback rather than leaving it to end as "client-vanished".
        g_interrupted = false;
        const auto previous = std::signal(SIGINT, [](int) { g_interrupted = true; });
        std::int64_t shown_bar = -1;
        std::optional<std::string> reason;
        while (!(reason = haptics.finished(id))) {
            if (const auto gone = watch->gone()) {
                // Signals are handled in the order they came: a Finished the daemon sent before
                // it left (SIGTERM) has been seen by now.
                if (!(reason = haptics.finished(id))) {
                    std::signal(SIGINT, previous);
                    err << "vibscore: " << *gone << " during playback " << id
                        << "; it did not finish\n";
                    return exit_failed;
                }
                break;
            }
            if (g_interrupted.exchange(false)) {
                haptics.Stop(id);
            }
            const auto position = haptics.position(id);
            if (position && static_cast<std::int64_t>(position->first) != shown_bar) {
                shown_bar = position->first;
                out << "playback " << id << ": bar " << shown_bar + 1 << "\n" << std::flush;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        std::signal(SIGINT, previous);
        out << "playback " << id << " " << *reason << "\n";
        return *reason == "completed" || *reason == "stopped" ? exit_ok : exit_failed;
    });
}

int stop(std::uint64_t id, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        haptics.Stop(id);
        haptics.take_signals();
        if (!haptics.any_stopped()) {
            out << (id == 0 ? std::string("none of your playbacks was playing")
                            : "playback " + std::to_string(id) + " had already ended")
                << "\n";
        } else {
            out << (id == 0 ? std::string("stopped your playback")
                            : "stopped playback " + std::to_string(id))
                << "\n";
        }
        return exit_ok;
    });
}

int stop_all(std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        haptics.StopAll();
        haptics.take_signals();
        out << (haptics.any_stopped() ? "stopped every playback" : "nothing was playing") << "\n";
        return exit_ok;
    });
}

int list(const std::string& kind, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        const auto entries = haptics.List(kind);
        for (const auto& entry : entries) {
            out << entry.get<0>() << "\t" << entry.get<1>() << "\n";
        }
        if (entries.empty()) {
            // Not an error, but an empty output alone looks like one: say where it looked.
            const std::string plural = kind.ends_with('s') ? kind : kind + "s";
            auto folders = haptics.RegistryFolders();
            err << "vibscore: vibscored has no " << plural << ": none shipped in "
                << folders["shipped"] << " (shipped = in vibscored.conf) and none composed in "
                << folders["store"] << " (store =)\n";
        }
        return exit_ok;
    });
}

int get(const std::string& kind, const std::string& name, std::ostream& out, std::ostream& err,
        bool device) {
    return with_daemon(err, [&](Haptics& haptics) {
        if (!device) {
            out << haptics.Get(kind, name);
            return exit_ok;
        }
        if (!kind.starts_with("clef")) {
            err << "vibscore: get --device: only a clef has a device form, not a " << kind << "\n";
            return exit_usage;
        }
        // The clef a bar written for NAME plays through here, as BarClefs tells it.
        const std::string probe = "<VibScore><Clef id=\"c\" href=\"" + name +
                                  ".clef.xml\"/><Bar clef=\"c\"><Rest length=\"quarter\"/>"
                                  "</Bar></VibScore>";
        const std::string device_clef = haptics.BarClefs(probe).at(0).get<1>();
        const std::string fitted_mark(render::kFittedMark);
        if (!device_clef.ends_with(fitted_mark)) {
            out << haptics.Get("clef", device_clef);
            return exit_ok;
        }
        // Fitted: the same pure fit vibscored makes, to the actuator it declares.
        const auto declared = declaration_of(haptics.Actuator());
        const Clef written = read_clef(haptics.Get("clef", name), "clef \"" + name + "\"");
        out << fitted_document(render::fit_clef(written, declared), name, declared);
        return exit_ok;
    });
}

int compose(const std::string& name, const std::string& file, const ClefSearch& clefs,
            std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        haptics.Compose(name, document_to_compose(haptics, file, clefs));
        out << "stored " << name << "\n";
        return exit_ok;
    });
}

int remove(const std::string& kind, const std::string& name, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        haptics.Delete(kind, name);
        out << "deleted " << kind << " " << name << "\n";
        return exit_ok;
    });
}

int describe_registry_score(const std::string& name, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        const std::string label = "score \"" + name + "\"";
        LoadedScore loaded;
        loaded.bundle =
            bind_clefs(read_score(haptics.Get("score", name), label), label,
                       [&](const ClefDeclaration& declaration, const SourceLocation& where) {
                           const auto clef = clef_name_in_href(declaration.href);
                           if (!clef) {
                               throw DocumentError(where, "href \"" + declaration.href +
                                                              "\" names no registry clef");
                           }
                           loaded.clef_origins[declaration.id] = kRegistryOrigin;
                           return read_clef(haptics.Get("clef", *clef), "clef \"" + *clef + "\"");
                       });
        describe_score(loaded, out);
        const std::string origin = haptics.Origin("score", name);
        out << "registry: "
            << (origin == "shipped" ? "shipped"
                : origin == "stored"
                    ? "stored"
                    : "stored, shadowing a shipped one (deleting it brings that back)")
            << "\n";
        out << "on this device:\n";
        const auto bars = haptics.BarClefs(name);
        for (std::size_t b = 0; b < bars.size(); ++b) {
            const auto& written = bars[b].get<0>();
            const auto& device = bars[b].get<1>();
            out << "  " << b + 1 << "  " << written
                << (device == written ? " (as written)" : " -> " + device) << "\n";
        }
        out << "actuator: " << actuator_line(haptics.Actuator()) << "\n"
            << actuator_source_line(haptics);
        return exit_ok;
    });
}

int list_drivers(std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        const std::string current = haptics.Driver();
        for (const auto& entry : haptics.ListDrivers()) {
            out << (entry.get<0>() == current ? "* " : "  ") << entry.get<0>() << "\t"
                << entry.get<1>() << "\n";
        }
        return exit_ok;
    });
}

int driver(const std::string& name, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        if (!name.empty() && haptics.Driver() == name) {
            // Switching would only end what plays and reopen the same backend.
            out << "driver " << name << " is already in use; nothing changed\n";
        } else if (!name.empty()) {
            haptics.SwitchDriver(name);
        }
        out << "driver " << haptics.Driver() << ":";
        for (const auto& capability : haptics.Capabilities()) {
            out << " " << capability;
        }
        out << "\n" << haptics.DriverReason() << "\n";
        const auto declared = haptics.Actuator();
        if (haptics.Driver() == "sim") {
            // The sim follows [actuator] when one is declared (drivers::make_sim_actuator); else
            // the model its [sim] section sets, whose numbers the bus does not publish: say where
            // they are rather than guess them.
            out << "sim: "
                << (declared.empty()
                        ? std::string("simulates the model its [sim] section sets (model, "
                                      "resonance-hz, q, spin-up-ms, spin-down-ms in "
                                      "vibscored.conf), no actuator being declared")
                        : "simulates the declared actuator: " + actuator_line(declared))
                << "\n";
        }
        out << "actuator: " << actuator_line(declared) << "\n" << actuator_source_line(haptics);
        return exit_ok;
    });
}

actuator::Declaration daemon_actuator() {
    std::map<std::string, std::string> settings;
    try {
        Haptics haptics(sdbus::createSystemBusConnection());
        settings = haptics.Actuator();
    } catch (const sdbus::Error& error) {
        throw std::runtime_error("cannot ask vibscored for its actuator: " + explain(error));
    }
    if (settings.empty()) {
        throw std::runtime_error(
            "vibscored declares no actuator ([actuator] in its vibscored.conf); give --actuator "
            "FILE");
    }
    return declaration_of(settings);
}

}  // namespace vibscore::client

namespace vibscore::client {

std::function<std::optional<std::string>(const std::string& name)> registry_clef_fetcher() {
    // One connection for every clef a command looks up, opened at the first.
    struct Link {
        std::unique_ptr<sdbus::IConnection> connection;
        std::unique_ptr<sdbus::IProxy> proxy;
        bool tried = false;
    };
    auto link = std::make_shared<Link>();
    return [link](const std::string& name) -> std::optional<std::string> {
        try {
            if (!link->tried) {
                link->tried = true;
                link->connection = sdbus::createSystemBusConnection();
                link->proxy = dbus::create_proxy(*link->connection, haptics1::kBusName,
                                                 haptics1::kObjectPath);
            }
            if (!link->proxy) {
                return std::nullopt;
            }
            std::string text;
            link->proxy->callMethod("Get")
                .onInterface(haptics1::kInterface)
                .withTimeout(std::chrono::seconds(2))
                .withArguments(std::string("clef"), name)
                .storeResultsTo(text);
            return text;
        } catch (const sdbus::Error&) {
            return std::nullopt;  // no bus, no daemon, no such clef: the next place is looked at
        }
    };
}

}  // namespace vibscore::client
