#include "client/bus_verbs.hpp"

#include <sdbus-c++/sdbus-c++.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>

#include "client/daemon_errors.hpp"
#include "client/offline_verbs.hpp"
#include "dbus/haptics1_names.hpp"
#include "haptics1-proxy.h"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"

namespace vibscore::client {

namespace {

std::atomic<bool> g_interrupted{false};

// A client of the daemon that remembers how each playback ended and where each one is.
class Haptics : public sdbus::ProxyInterfaces<org::vibscore::Haptics1_proxy> {
  public:
    explicit Haptics(std::unique_ptr<sdbus::IConnection> connection)
        : ProxyInterfaces(*connection, haptics1::kBusName, haptics1::kObjectPath),
          connection_(std::move(connection)) {
        registerProxy();
    }
    ~Haptics() {
        connection_->leaveEventLoop();
        unregisterProxy();
    }
    void listen() { connection_->enterEventLoopAsync(); }

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
    }
    return exit_failed;
}

// A file is sent whole, so the daemon needs no access to it; anything else is a registry name.
std::string score_argument(const std::string& score) {
    return is_document_file(score) ? read_document_file(score) : score;
}

// The registry clef an href names: "lra-phone" for "lra-phone.clef.xml" or "lra-phone.xml".
std::string registry_clef_name(std::string href) {
    for (const std::string suffix : {".clef.xml", ".xml"}) {
        if (href.ends_with(suffix)) {
            href.resize(href.size() - suffix.size());
            break;
        }
    }
    return href;
}

}  // namespace

bool is_document_file(const std::string& argument) {
    std::error_code ignored;
    return argument.find('/') != std::string::npos ||
           std::filesystem::is_regular_file(argument, ignored);
}

int play(const PlayRequest& request, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        std::map<std::string, sdbus::Variant> options;
        if (!request.usage.empty())
            options["usage"] = sdbus::Variant(request.usage);
        if (request.repeat != 0)
            options["repeat"] = sdbus::Variant(std::int32_t{request.repeat});
        if (!request.clef.empty())
            options["clef"] = sdbus::Variant(request.clef);
        if (request.intensity >= 0.0)
            options["intensity"] = sdbus::Variant(request.intensity);
        if (request.wait) {
            haptics.listen();
        }
        const auto id = haptics.Play(score_argument(request.score), options);
        if (!request.wait) {
            out << id << "\n";
            return exit_ok;
        }
        // Ctrl-C stops the playback rather than leaving it to end as "client-vanished".
        g_interrupted = false;
        const auto previous = std::signal(SIGINT, [](int) { g_interrupted = true; });
        std::int64_t shown_bar = -1;
        std::optional<std::string> reason;
        while (!(reason = haptics.finished(id))) {
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
        out << (id == 0 ? std::string("stopped your playbacks") : "stopped " + std::to_string(id))
            << "\n";
        return exit_ok;
    });
}

int list(const std::string& kind, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        for (const auto& entry : haptics.List(kind)) {
            out << entry.get<0>() << "\t" << entry.get<1>() << "\n";
        }
        return exit_ok;
    });
}

int get(const std::string& kind, const std::string& name, std::ostream& out, std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        out << haptics.Get(kind, name);
        return exit_ok;
    });
}

int compose(const std::string& name, const std::string& file, std::ostream& out,
            std::ostream& err) {
    return with_daemon(err, [&](Haptics& haptics) {
        haptics.Compose(name, read_document_file(file));
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
        const auto bundle =
            bind_clefs(read_score(haptics.Get("score", name), label), label,
                       [&](const ClefDeclaration& declaration, const SourceLocation&) {
                           const auto clef = registry_clef_name(declaration.href);
                           return read_clef(haptics.Get("clef", clef), "clef \"" + clef + "\"");
                       });
        describe_score(bundle, out);
        out << "on this device:\n";
        const auto bars = haptics.BarClefs(name);
        for (std::size_t b = 0; b < bars.size(); ++b) {
            const auto& written = bars[b].get<0>();
            const auto& device = bars[b].get<1>();
            out << "  " << b + 1 << "  " << written
                << (device == written ? " (as written)" : " -> " + device) << "\n";
        }
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
        if (!name.empty()) {
            haptics.SwitchDriver(name);
        }
        out << "driver " << haptics.Driver() << ":";
        for (const auto& capability : haptics.Capabilities()) {
            out << " " << capability;
        }
        out << "\n";
        return exit_ok;
    });
}

}  // namespace vibscore::client
