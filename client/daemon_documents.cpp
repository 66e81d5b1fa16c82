#include "client/daemon_documents.hpp"

#include <sdbus-c++/sdbus-c++.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include "client/bus_verbs.hpp"
#include "client/editor/daemon_errors.hpp"
#include "daemon/render/fitting/clef_fit.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"
#include "score/score_xml.hpp"

namespace vibscore::client {

namespace {

// One connection to vibscored for the calls of one command.
class Daemon {
  public:
    Daemon() {
        try {
            connection_ = sdbus::createSystemBusConnection();
            proxy_ = dbus::create_proxy(*connection_, haptics1::kBusName, haptics1::kObjectPath);
        } catch (const sdbus::Error& error) {
            throw std::runtime_error("cannot reach vibscored: " +
                                     describe_daemon_error(error.getName(), error.getMessage()));
        }
    }

    std::string get(const std::string& kind, const std::string& name) {
        std::string text;
        guarded([&] {
            proxy_->callMethod("Get")
                .onInterface(haptics1::kInterface)
                .withTimeout(kTimeout)
                .withArguments(kind, name)
                .storeResultsTo(text);
        });
        return text;
    }

    // The clef a bar written for registry clef `name` plays through here ("NAME (fitted)" when
    // fitted), asked as `vibscore get clef NAME --device` asks it.
    std::string device_clef(const std::string& name) {
        const std::string probe = "<VibScore><Clef id=\"c\" href=\"" + name +
                                  ".clef.xml\"/><Bar clef=\"c\"><Rest length=\"quarter\"/>"
                                  "</Bar></VibScore>";
        std::vector<sdbus::Struct<std::string, std::string>> bars;
        guarded([&] {
            proxy_->callMethod("BarClefs")
                .onInterface(haptics1::kInterface)
                .withTimeout(kTimeout)
                .withArguments(probe)
                .storeResultsTo(bars);
        });
        if (bars.empty()) {
            throw std::runtime_error("vibscored's BarClefs gave no bar for clef \"" + name + "\"");
        }
        return bars.front().get<1>();
    }

  private:
    static constexpr std::chrono::seconds kTimeout{5};

    template <typename Call>
    static void guarded(const Call& call) {
        try {
            call();
        } catch (const sdbus::Error& error) {
            throw std::runtime_error(describe_daemon_error(error.getName(), error.getMessage()));
        }
    }

    std::unique_ptr<sdbus::IConnection> connection_;
    std::unique_ptr<sdbus::IProxy> proxy_;
};

Clef fitted(const Clef& written, const actuator::Declaration& declared) {
    try {
        return render::fit_clef(written, declared).clef;
    } catch (const render::ClefFitError&) {
        return written;  // vibscored plays a clef it cannot fit as written, and so is it drawn
    }
}

}  // namespace

std::function<std::string(const std::string& name)> registry_score_fetcher() {
    return [](const std::string& name) {
        Daemon daemon;
        return daemon.get("score", name);
    };
}

DeviceClefBinder daemon_clef_binder() {
    return [](const LoadedScore& written) {
        Daemon daemon;
        std::optional<actuator::Declaration> declared;
        const auto actuator = [&]() -> const actuator::Declaration& {
            if (!declared) {
                declared = daemon_actuator();
            }
            return *declared;
        };
        const std::string fitted_mark(render::kFittedMark);
        DeviceBound bound;
        std::map<std::string, Clef, std::less<>> clefs;  // by clef id
        for (const auto& declaration : written.bundle.score.clefs) {
            const Clef& clef = written.bundle.clefs.at(declaration.id);
            const auto name = clef_name_in_href(declaration.href);
            const auto origin = written.clef_origins.find(declaration.id);
            const bool from_registry =
                name && origin != written.clef_origins.end() && origin->second == kRegistryOrigin;
            std::string device;
            if (name) {
                try {
                    device = daemon.device_clef(*name);
                } catch (const std::runtime_error&) {
                    device.clear();  // not a clef vibscored has: it is sent with the score
                }
            }
            const std::string shown_name =
                name ? *name : std::filesystem::path(declaration.href).filename().string();
            std::string shown;
            if (device.ends_with(fitted_mark)) {
                // The registry's clef fitted, or the sent one (vibscored fits those too).
                clefs[declaration.id] = fitted(
                    from_registry ? read_clef(daemon.get("clef", *name), "clef \"" + *name + "\"")
                                  : clef,
                    actuator());
                shown = shown_name + fitted_mark;
            } else if (from_registry && !device.empty() && device != *name) {
                clefs[declaration.id] =
                    read_clef(daemon.get("clef", device), "clef \"" + device + "\"");
                shown = device;
            } else {
                clefs[declaration.id] = clef;
                shown = shown_name;
            }
            bound.names[declaration.id] = shown;
            bound.said +=
                (bound.said.empty() ? "" : ", ") +
                (shown == shown_name ? shown_name + " (as written)" : shown_name + " -> " + shown);
        }
        bound.bundle =
            bind_clefs(ParsedScore{written.bundle.score, written.bundle.where}, written.bundle.file,
                       [&](const ClefDeclaration& declaration, const SourceLocation&) {
                           return clefs.at(declaration.id);
                       });
        return bound;
    };
}

}  // namespace vibscore::client
