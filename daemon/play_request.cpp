#include "daemon/play_request.hpp"

#include <memory>
#include <string>

#include "common/number_text.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "daemon/request_error.hpp"
#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

namespace {

RequestError invalid(const std::string& message) {
    return RequestError(RequestError::Code::invalid, message);
}

RequestError out_of_range(const std::string& message) {
    return RequestError(RequestError::Code::out_of_range, message);
}

template <typename T>
T option_value(const std::string& key, const sdbus::Variant& value, const char* signature,
               const char* type_name) {
    const std::string held = dbus::variant_signature(value);
    if (held != signature) {
        throw invalid("option \"" + key + "\" must be " + type_name + " (" + signature + "), not " +
                      held);
    }
    return value.get<T>();
}

bool is_inline_document(const std::string& score) {
    const auto first = score.find_first_not_of(" \t\r\n");
    return first != std::string::npos && score[first] == '<';
}

}  // namespace

PlayOptions parse_play_options(const std::map<std::string, sdbus::Variant>& options) {
    PlayOptions parsed;
    for (const auto& [key, value] : options) {
        if (key == "usage") {
            const auto name = option_value<std::string>(key, value, "s", "a string");
            const auto usage = parse_usage(name);
            if (!usage) {
                throw invalid("unknown usage \"" + name + "\" (expected " +
                              std::string(usage_names()) + ")");
            }
            parsed.usage = *usage;
        } else if (key == "repeat") {
            parsed.repeat = option_value<std::int32_t>(key, value, "i", "an int32");
            if (parsed.repeat < -1) {
                throw out_of_range("repeat " + std::to_string(parsed.repeat) +
                                   " is outside -1.. (0 once, n more times, -1 until stopped)");
            }
        } else if (key == "intensity") {
            parsed.intensity = option_value<double>(key, value, "d", "a double");
            if (!(parsed.intensity >= 0.0 && parsed.intensity <= 1.0)) {
                throw out_of_range("intensity " + number_text(parsed.intensity) +
                                   " is outside 0..1");
            }
        } else if (key == "clef") {
            parsed.clef = option_value<std::string>(key, value, "s", "a string");
        } else if (key == "start-bar") {
            parsed.start_bar = option_value<std::uint32_t>(key, value, "u", "a uint32");
        } else if (key == "clefs") {
            parsed.clef_documents = option_value<std::map<std::string, std::string>>(
                key, value, "a{ss}", "a dictionary of strings");
        } else {
            throw invalid("unknown option \"" + key +
                          "\" (expected usage, repeat, intensity, clef, start-bar, clefs)");
        }
    }
    return parsed;
}

std::size_t document_bytes(const std::string& score, const PlayOptions& options) {
    std::size_t bytes = is_inline_document(score) ? score.size() : 0;
    for (const auto& [href, document] : options.clef_documents) {
        bytes += href.size() + document.size();
    }
    return bytes;
}

std::size_t document_bytes(const std::string& score,
                           const std::map<std::string, sdbus::Variant>& options) {
    PlayOptions counted;
    const auto clefs = options.find("clefs");
    if (clefs != options.end() && dbus::variant_signature(clefs->second) == "a{ss}") {
        counted.clef_documents = clefs->second.get<std::map<std::string, std::string>>();
    }
    return document_bytes(score, counted);
}

ScoreToPlay find_score_to_play(const Registry& registry, const std::string& score,
                               const PlayOptions& options, const DeviceClefs& device_clefs,
                               ClefFitCache* fit_cache) {
    const std::string& clef_override = options.clef;
    ScoreToPlay found;
    if (is_inline_document(score)) {
        found.bundle = registry.inline_score(score, options.clef_documents);
        found.label = "<inline>";
    } else {
        if (!options.clef_documents.empty()) {
            throw invalid("option \"clefs\" goes with an inline score, not registry score \"" +
                          score + "\"");
        }
        found.bundle = registry.score(score);
        found.label = score;
    }
    if (!clef_override.empty()) {
        const Clef clef = registry.clef(clef_override);
        found.bundle =
            bind_clefs(ParsedScore{found.bundle.score, found.bundle.where}, found.bundle.file,
                       [&](const ClefDeclaration&, const SourceLocation&) { return clef; });
    } else if (!device_clefs.empty()) {
        found.bundle = bind_device_clefs(registry, found.bundle, device_clefs,
                                         options.clef_documents, fit_cache);
    }
    return found;
}

PlaybackRequest make_playback_request(const ScoreToPlay& score, const PlayOptions& options,
                                      double separation_s) {
    const auto bars = score.bundle.score.bars.size();
    if (options.start_bar >= bars) {
        throw out_of_range("start-bar " + std::to_string(options.start_bar) +
                           " is past the last bar (the score has " + std::to_string(bars) + ")");
    }
    render::RenderOptions render_options;
    render_options.separation_s = separation_s;
    render_options.start_bar = options.start_bar;
    auto performance = std::make_shared<const render::Performance>(score.bundle, render_options);

    PlaybackRequest request;
    request.label = score.label;
    request.duration_s = performance->duration();
    request.cues = std::make_shared<render::ScheduleSource>(std::move(performance));
    request.usage = options.usage;
    request.repeat = options.repeat;
    request.intensity = options.intensity;
    return request;
}

}  // namespace vibscore::daemon
