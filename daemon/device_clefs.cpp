#include "daemon/device_clefs.hpp"

#include <cstddef>

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

}  // namespace

std::string DeviceClefs::for_written(std::string_view written) const {
    const auto found = by_written.find(written);
    if (found != by_written.end()) {
        return found->second;
    }
    return otherwise.empty() ? std::string(written) : otherwise;
}

std::string describe(const DeviceClefs& clefs) {
    std::string text;
    for (const auto& [written, device] : clefs.by_written) {
        text += (text.empty() ? "" : ", ") + written + " -> " + device;
    }
    if (!clefs.otherwise.empty()) {
        text += (text.empty() ? "" : ", ") + std::string("* -> ") + clefs.otherwise;
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
                              const std::map<std::string, std::string>& sent) {
    std::map<std::string, Clef, std::less<>> device_clefs = written.clefs;  // by declaration id
    for (const auto& [id, name] : written_clef_names(written, sent)) {
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
