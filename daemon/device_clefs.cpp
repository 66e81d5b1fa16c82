#include "daemon/device_clefs.hpp"

#include <cstddef>

#include "common/log.hpp"
#include "daemon/render/fitting/clef_check.hpp"
#include "daemon/render/fitting/clef_fit.hpp"

namespace vibscore::daemon {

namespace {

// The registry clef each declaration of the score names, by declaration id; declarations whose
// href is in `sent` (clefs the caller sent along) are left out.
std::map<std::string, std::string, std::less<>> written_clef_names(
    const ScoreBundle& bundle, const std::map<std::string, std::string>& sent = {}) {
    std::map<std::string, std::string, std::less<>> names;
    const auto& declarations = bundle.score.clefs;
    for (std::size_t i = 0; i < declarations.size(); ++i) {
        if (sent.contains(declarations[i].href)) {
            continue;
        }
        const SourceLocation declared_at =
            i < bundle.where.clefs.size() ? bundle.where.clefs[i] : bundle.where.document;
        names[declarations[i].id] = clef_name_of(declarations[i], declared_at);
    }
    return names;
}

// The written clef fitted to the actuator; as written when it cannot be fitted (said in the log).
Clef fit_now(const Clef& written, const std::string& name, const actuator::Declaration& actuator) {
    try {
        return render::fit_clef(written, actuator).clef;
    } catch (const render::ClefFitError& error) {
        log::warning("clef \"" + name + "\" plays as written: cannot fit it: " + error.what());
        return written;
    }
}

// Kept in `cache` when there is one: "plays as written" is kept too (and logged once).
Clef fitted(const Clef& written, const std::string& name, const actuator::Declaration& actuator,
            ClefFitCache* cache) {
    if (cache == nullptr) {
        return fit_now(written, name, actuator);
    }
    return cache->fitted(name, written, actuator,
                         [&](const Clef& clef) { return fit_now(clef, name, actuator); });
}

void log_fit(const std::string& name, const Clef& written, const actuator::Declaration& actuator) {
    try {
        const auto fit = render::fit_clef(written, actuator);
        if (fit.notes.empty()) {
            log::info("clef \"" + name + "\" fits the actuator as written");
        }
        for (const auto& note : fit.notes) {
            log::info("clef \"" + name + "\" fitted to the actuator: " + note);
        }
        for (const auto& warning : render::clef_warnings(fit.clef, actuator)) {
            log::warning("clef \"" + name + "\" (fitted): " + warning);
        }
    } catch (const render::ClefFitError& error) {
        log::warning("clef \"" + name + "\" plays as written: cannot fit it: " + error.what());
    }
}

}  // namespace

void log_clef_fits(const Registry& registry, const DeviceClefs& clefs) {
    if (!clefs.fit_to) {
        return;
    }
    for (const auto& entry : registry.list(DocumentKind::clef)) {
        if (!clefs.fits(entry.name)) {
            continue;
        }
        try {
            log_fit(entry.name, registry.clef(entry.name), *clefs.fit_to);
        } catch (const std::exception& error) {
            log::warning("clef \"" + entry.name + "\" cannot be read to fit: " + error.what());
        }
    }
}

void log_stored_clef(const Registry& registry, const DeviceClefs& clefs,
                     const std::optional<actuator::Declaration>& actuator,
                     const std::string& name) {
    try {
        if (clefs.fits(name)) {
            log_fit(name, registry.clef(name), *clefs.fit_to);
        } else if (actuator) {
            for (const auto& warning : render::clef_warnings(registry.clef(name), *actuator)) {
                log::warning("clef \"" + name + "\": " + warning);
            }
        }
    } catch (const std::exception& error) {
        // Only the log is lost: the clef is stored.
        log::warning("clef \"" + name + "\" cannot be read to check: " + error.what());
    }
}

std::string DeviceClefs::for_written(std::string_view written) const {
    const auto found = by_written.find(written);
    if (found != by_written.end()) {
        return found->second;
    }
    if (!otherwise.empty()) {
        return otherwise;
    }
    return std::string(written) + (fit_to ? std::string(render::kFittedMark) : std::string());
}

std::string describe(const DeviceClefs& clefs) {
    std::string text;
    for (const auto& [written, device] : clefs.by_written) {
        text += (text.empty() ? "" : ", ") + written + " -> " + device;
    }
    if (!clefs.otherwise.empty()) {
        text += (text.empty() ? "" : ", ") + std::string("* -> ") + clefs.otherwise;
    }
    if (clefs.fit_to) {
        text += (text.empty() ? "" : ", ") + std::string("fit = auto (") +
                (clefs.otherwise.empty() ? "every other clef fitted to the actuator"
                                         : "no clef left to fit: * maps them all") +
                ")";
    }
    return text.empty() ? "none" : text;
}

std::vector<BarClef> bar_clefs(const ScoreBundle& written, const DeviceClefs& clefs) {
    const auto names = written_clef_names(written);
    std::vector<BarClef> bars;
    bars.reserve(written.score.bars.size());
    for (const auto& bar : written.score.bars) {
        const auto& name = names.at(bar.clef);
        bars.push_back({name, clefs.for_written(name)});
    }
    return bars;
}

ScoreBundle bind_device_clefs(const Registry& registry, const ScoreBundle& written,
                              const DeviceClefs& clefs,
                              const std::map<std::string, std::string>& sent, ClefFitCache* cache) {
    std::map<std::string, Clef, std::less<>> device_clefs = written.clefs;  // by declaration id
    if (clefs.fit_to) {
        for (const auto& declaration : written.score.clefs) {
            if (sent.contains(declaration.href)) {
                device_clefs.insert_or_assign(
                    declaration.id, fitted(written.clefs.at(declaration.id), declaration.href,
                                           *clefs.fit_to, cache));
            }
        }
    }
    for (const auto& [id, name] : written_clef_names(written, sent)) {
        if (clefs.fits(name)) {
            device_clefs.insert_or_assign(id,
                                          fitted(registry.clef(name), name, *clefs.fit_to, cache));
            continue;
        }
        const auto device = clefs.for_written(name);
        if (!registry.contains(DocumentKind::clef, device)) {
            throw RegistryError(RegistryError::Code::not_found,
                                "no clef \"" + device + "\" in the registry: vibscored.conf's " +
                                    "[clefs] plays clef \"" + name + "\" through it");
        }
        device_clefs.insert_or_assign(id, registry.clef(device));
    }
    return bind_clefs(ParsedScore{written.score, written.where}, written.file,
                      [&](const ClefDeclaration& declaration, const SourceLocation&) {
                          return device_clefs.at(declaration.id);
                      });
}

}  // namespace vibscore::daemon
