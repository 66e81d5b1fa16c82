#include "client/formats/ahap.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "client/formats/grid_fit.hpp"
#include "client/formats/json_reading.hpp"
#include "score/limits.hpp"
#include "score/xml_support.hpp"

namespace vibscore::formats {

namespace {

using Json = nlohmann::ordered_json;

Json parameter(const char* id, double value) {
    return Json{{"ParameterID", id}, {"ParameterValue", value}};
}

Json curve(const char* id, double time, const std::vector<std::pair<double, double>>& points) {
    Json control_points = Json::array();
    for (const auto& [at, value] : points) {
        control_points.push_back(Json{{"Time", at}, {"ParameterValue", value}});
    }
    return Json{{"ParameterCurve",
                 {{"ParameterID", id},
                  {"Time", time},
                  {"ParameterCurveControlPoints", std::move(control_points)}}}};
}

// A parameter curve, as Core Haptics applies it to every event: linear between its points,
// holding its last value until another curve of the same parameter begins.
struct Curve {
    double start = 0.0;
    std::vector<std::pair<double, double>> points;  // absolute time, value

    double value_at(double t) const {
        if (t <= points.front().first) {
            return points.front().second;
        }
        // The first point at or after t; the points' times never go back.
        const auto after =
            std::lower_bound(points.begin(), points.end(), t,
                             [](const auto& point, double at) { return point.first < at; });
        if (after == points.end()) {
            return points.back().second;
        }
        const auto& [t1, v1] = *after;
        const auto& [t0, v0] = *std::prev(after);
        return t1 > t0 ? v0 + (v1 - v0) * (t - t0) / (t1 - t0) : v1;
    }
};

// The control a parameter has at time t: that of the latest curve begun by then (`at_start`:
// a curve beginning exactly at t counts; of curves beginning together the last in the file), or
// `neutral` before any. `curves` is in order of start, stably (sort_curves), so each look-up
// is a binary search: a file of many events and many curves costs n log n, not n squared.
double control_at(const std::vector<Curve>& curves, double t, bool at_start, double neutral) {
    const auto by_start = [](double at, const Curve& curve) { return at < curve.start; };
    const auto begun =
        at_start ? std::upper_bound(curves.begin(), curves.end(), t, by_start)
                 : std::lower_bound(curves.begin(), curves.end(), t,
                                    [](const Curve& curve, double at) { return curve.start < at; });
    return begun == curves.begin() ? neutral : std::prev(begun)->value_at(t);
}

void sort_curves(std::vector<Curve>& curves) {
    std::stable_sort(curves.begin(), curves.end(),
                     [](const Curve& a, const Curve& b) { return a.start < b.start; });
}

struct HapticEvent {
    double time = 0.0, duration = 0.0;
    double intensity = 1.0, sharpness = 0.5;
};

// What Apple's parser takes though its documents forbid it, for the reader to say once each,
// up to limits::diagnostics of them.
class Warnings {
  public:
    explicit Warnings(const JsonDocument& document) : document_(document) {}

    void add(std::ptrdiff_t offset, std::string message) {
        if (list_.size() < limits::diagnostics) {
            list_.push_back({document_.where(offset), std::move(message)});
        } else {
            ++more_;
        }
    }
    std::vector<Diagnostic> take() && {
        if (more_ > 0) {
            list_.push_back({{document_.file()}, std::to_string(more_) + " more like these"});
        }
        return std::move(list_);
    }

  private:
    const JsonDocument& document_;
    std::vector<Diagnostic> list_;
    std::size_t more_ = 0;
};

class AhapReader {
  public:
    AhapReader(const JsonDocument& document, DiagnosticSink& sink)
        : json_(document, sink), document_(document), warnings_(document) {
        for (const auto offset : document.trailing_commas()) {
            warnings_.add(offset,
                          "a trailing comma, which JSON does not allow; Apple's parser (and "
                          "Apple's own sample files) take it, and so does vibscore");
        }
    }

    std::vector<Diagnostic> warnings() && { return std::move(warnings_).take(); }

    void read() {
        const auto& root = document_.root();
        if (!json_.expect(root, JsonValue::Kind::object, "an AHAP file")) {
            return;
        }
        json_.check_keys(root, {"Version", "Metadata", "Pattern"}, "the AHAP file");
        if (const auto* version = root.find("Version")) {
            json_.number(*version, "Version", 0.0, 1e6);
        }
        if (const auto* metadata = root.find("Metadata");
            metadata != nullptr && json_.expect(*metadata, JsonValue::Kind::object, "Metadata")) {
            if (const auto* project = metadata->find("Project")) {
                title = json_.string(*project, "Metadata Project").value_or("");
            }
            // vibscore's exports record their tempo; Metadata is free-form, so anything else
            // under that key is left alone.
            if (const auto* tempo = metadata->find("Tempo");
                tempo != nullptr && tempo->kind == JsonValue::Kind::number &&
                tempo->number >= limits::min_tempo_s && tempo->number <= limits::max_tempo_s) {
                this->tempo = tempo->number;
            }
        }
        const auto* pattern = json_.member(root, "Pattern", "the AHAP file");
        if (pattern == nullptr || !json_.expect(*pattern, JsonValue::Kind::array, "Pattern")) {
            return;
        }
        for (const auto& entry : pattern->items) {
            read_entry(entry);
        }
    }

    std::string title;
    std::optional<double> tempo;
    std::vector<HapticEvent> events;
    std::vector<Curve> intensity_curves, sharpness_curves;
    // Where the last parameter or curve begins: Core Haptics counts a pattern's length to the
    // end of its last event or the start of its last parameter, whichever is later.
    double last_parameter = 0.0;

  private:
    void read_entry(const JsonValue& entry) {
        if (!json_.expect(entry, JsonValue::Kind::object, "a Pattern entry")) {
            return;
        }
        if (entry.members.size() != 1) {
            json_.report(entry, "a Pattern entry holds one of Event, ParameterCurve or Parameter");
            return;
        }
        const auto& [key, key_offset, value] = entry.members.front();
        if (!json_.expect(value, JsonValue::Kind::object, key)) {
            return;
        }
        if (key == "Event") {
            read_event(value);
        } else if (key == "ParameterCurve") {
            read_curve(value);
        } else if (key == "Parameter") {
            read_parameter(value);
        } else {
            json_.check_keys(entry, {"Event", "ParameterCurve", "Parameter"}, "a Pattern entry");
        }
    }

    void read_event(const JsonValue& event) {
        json_.check_keys(
            event,
            {"Time", "EventType", "EventDuration", "EventParameters", "EventWaveformPath",
             "EventWaveformLoopEnabled", "EventWaveformUseVolumeEnvelope"},
            "an Event");
        const auto* type_value = json_.member(event, "EventType", "the Event");
        const auto type = type_value ? json_.string(*type_value, "EventType") : std::nullopt;
        const bool haptic = type == "HapticTransient" || type == "HapticContinuous";
        if (type && !haptic && type != "AudioContinuous" && type != "AudioCustom") {
            json_.report(*type_value, "unknown EventType \"" + *type +
                                          "\" (expected HapticTransient, HapticContinuous, "
                                          "AudioContinuous or AudioCustom)");
        }
        HapticEvent read;
        if (const auto* time = json_.member(event, "Time", "the Event")) {
            read.time = json_.number(*time, "Time", 0.0, limits::max_score_seconds).value_or(0.0);
        }
        const auto* duration = event.find("EventDuration");
        if (type == "HapticContinuous") {
            if (duration == nullptr) {
                json_.report(event, "a HapticContinuous event needs an EventDuration");
            } else {
                read.duration =
                    json_.number(*duration, "EventDuration", 0.0, ahap_max_event_s).value_or(0.0);
            }
        } else if (duration != nullptr) {
            json_.number(*duration, "EventDuration", 0.0, limits::max_score_seconds);
        }
        if (const auto* parameters = event.find("EventParameters");
            parameters != nullptr &&
            json_.expect(*parameters, JsonValue::Kind::array, "EventParameters")) {
            for (const auto& parameter : parameters->items) {
                read_event_parameter(parameter, read);
            }
        }
        if (haptic) {
            within_limits(event, read);
            events.push_back(read);
        }
    }

    // A score's length, checked event by event so that a pattern past it is refused where it
    // passes it. (Its symbols need no check here: the shortest event takes some 50 bytes, so a
    // 1 MiB file holds about 20,000.)
    void within_limits(const JsonValue& event, const HapticEvent& read) {
        if (past_the_hour(read.time + read.duration)) {
            json_.report(event, "too long for a score: the event ends at " +
                                    xml::format_number(read.time + read.duration) +
                                    " s; a score lasts at most " +
                                    xml::format_number(limits::max_score_seconds) + " s");
        }
    }

    void read_event_parameter(const JsonValue& parameter, HapticEvent& event) {
        if (!json_.expect(parameter, JsonValue::Kind::object, "an event parameter")) {
            return;
        }
        json_.check_keys(parameter, {"ParameterID", "ParameterValue"}, "an event parameter");
        const auto* id_value = json_.member(parameter, "ParameterID", "the event parameter");
        const auto* value = json_.member(parameter, "ParameterValue", "the event parameter");
        const auto id = id_value ? json_.string(*id_value, "ParameterID") : std::nullopt;
        if (!id || value == nullptr) {
            return;
        }
        static const std::vector<std::string> kOthers{"AttackTime", "DecayTime",      "ReleaseTime",
                                                      "Sustained",  "AudioVolume",    "AudioPan",
                                                      "AudioPitch", "AudioBrightness"};
        if (*id == "HapticIntensity") {
            event.intensity = parameter_value(*value, *id, 0.0, 1.0).value_or(event.intensity);
        } else if (*id == "HapticSharpness") {
            event.sharpness = parameter_value(*value, *id, 0.0, 1.0).value_or(event.sharpness);
        } else if (std::find(kOthers.begin(), kOthers.end(), *id) != kOthers.end()) {
            parameter_value(*value, *id, -1.0, 1.0);  // no counterpart in a score
        } else {
            json_.report(*id_value, "unknown event ParameterID \"" + *id + "\"");
        }
    }

    // The curves a score can use; the others (attack, decay, release, audio) are read and
    // checked but have no counterpart in a score.
    std::vector<Curve>* curves_for(const JsonValue& id_value, const std::string& id, double& min) {
        min = -1.0;
        if (id == "HapticIntensityControl") {
            min = 0.0;
            return &intensity_curves;
        }
        if (id == "HapticSharpnessControl") {
            return &sharpness_curves;
        }
        static const std::vector<std::string> kOthers{
            "HapticAttackTimeControl", "HapticDecayTimeControl", "HapticReleaseTimeControl",
            "AudioVolumeControl",      "AudioPanControl",        "AudioPitchControl",
            "AudioBrightnessControl",  "AudioAttackTimeControl", "AudioDecayTimeControl",
            "AudioReleaseTimeControl"};
        if (std::find(kOthers.begin(), kOthers.end(), id) == kOthers.end()) {
            json_.report(id_value, "unknown ParameterID \"" + id + "\" for a curve");
        }
        return nullptr;
    }

    void read_curve(const JsonValue& object) {
        json_.check_keys(object, {"ParameterID", "Time", "ParameterCurveControlPoints"},
                         "a ParameterCurve");
        const auto* id_value = json_.member(object, "ParameterID", "the ParameterCurve");
        const auto* time = json_.member(object, "Time", "the ParameterCurve");
        const auto* points =
            json_.member(object, "ParameterCurveControlPoints", "the ParameterCurve");
        const auto id = id_value ? json_.string(*id_value, "ParameterID") : std::nullopt;
        if (!id || time == nullptr || points == nullptr ||
            !json_.expect(*points, JsonValue::Kind::array, "ParameterCurveControlPoints")) {
            return;
        }
        double min = 0.0;
        auto* target = curves_for(*id_value, *id, min);
        Curve curve;
        curve.start = json_.number(*time, "Time", 0.0, limits::max_score_seconds).value_or(0.0);
        last_parameter = std::max(last_parameter, curve.start);
        for (const auto& point : points->items) {
            if (!json_.expect(point, JsonValue::Kind::object, "a control point")) {
                continue;
            }
            json_.check_keys(point, {"Time", "ParameterValue"}, "a control point");
            const auto* at = json_.member(point, "Time", "the control point");
            const auto* value = json_.member(point, "ParameterValue", "the control point");
            if (at == nullptr || value == nullptr) {
                continue;
            }
            const auto t = json_.number(*at, "control point Time", 0.0, limits::max_score_seconds);
            const auto v = parameter_value(*value, *id + " value", min, 1.0);
            if (t && v) {
                if (!curve.points.empty() && curve.start + *t < curve.points.back().first) {
                    json_.report(point, "control point times must not go back");
                }
                curve.points.emplace_back(curve.start + *t, *v);
            }
        }
        if (points->items.empty()) {
            json_.report(*points, "a ParameterCurve needs at least one control point");
        }
        if (target != nullptr && !curve.points.empty()) {
            target->push_back(std::move(curve));
        }
    }

    // A dynamic parameter: the control jumps to a value at a time.
    void read_parameter(const JsonValue& object) {
        json_.check_keys(object, {"ParameterID", "Time", "ParameterValue"}, "a Parameter");
        const auto* id_value = json_.member(object, "ParameterID", "the Parameter");
        const auto* time = json_.member(object, "Time", "the Parameter");
        const auto* value = json_.member(object, "ParameterValue", "the Parameter");
        const auto id = id_value ? json_.string(*id_value, "ParameterID") : std::nullopt;
        if (!id || time == nullptr || value == nullptr) {
            return;
        }
        double min = 0.0;
        auto* target = curves_for(*id_value, *id, min);
        const auto t = json_.number(*time, "Time", 0.0, limits::max_score_seconds);
        const auto v = parameter_value(*value, *id + " value", min, 1.0);
        if (t) {
            last_parameter = std::max(last_parameter, *t);
        }
        if (target != nullptr && t && v) {
            target->push_back({*t, {{*t, *v}}});
        }
    }

    // A parameter's value: a finite number, kept within [min, max] as Core Haptics keeps it
    // (its documentation: values outside a parameter's range are clamped), with a warning.
    std::optional<double> parameter_value(const JsonValue& value, const std::string& what,
                                          double min, double max) {
        const auto read = json_.number(value, what, -std::numeric_limits<double>::max(),
                                       std::numeric_limits<double>::max());
        if (!read || (*read >= min && *read <= max)) {
            return read;
        }
        const double clamped = std::clamp(*read, min, max);
        warnings_.add(value.offset, what + " " + xml::format_number(*read) + " is out of range (" +
                                        xml::format_number(min) + " to " + xml::format_number(max) +
                                        "): read as " + xml::format_number(clamped) +
                                        ", as Core Haptics clamps it");
        return clamped;
    }

    JsonReader json_;
    const JsonDocument& document_;
    Warnings warnings_;
};

// The strength at each bend strictly inside (from, to): two points where a curve begins with a
// jump. None when every bend lies on the straight ramp between the ends, which the note's own
// hairpin or glide already draws.
template <typename StrengthAt>
std::vector<std::pair<double, double>> bends_within(const std::vector<double>& bends, double from,
                                                    double to, double start, double end,
                                                    const StrengthAt& strength_at,
                                                    std::size_t& looked_at) {
    constexpr double kStraight = 0.004;  // as grid_fit's slack for 8-bit and float noise
    std::vector<std::pair<double, double>> points;
    bool bent = false;
    for (auto it = std::upper_bound(bends.begin(), bends.end(), from);
         it != bends.end() && *it < to; ++it) {
        ++looked_at;
        if (looked_at > limits::symbols) {
            return {};  // the caller refuses the file
        }
        const double before = strength_at(*it, false), after = strength_at(*it, true);
        const double straight = start + (end - start) * (*it - from) / (to - from);
        bent = bent || std::abs(before - straight) > kStraight ||
               std::abs(after - straight) > kStraight;
        if (std::abs(before - after) > kStraight) {
            points.emplace_back(*it, before);
        }
        points.emplace_back(*it, after);
    }
    return bent ? points : std::vector<std::pair<double, double>>{};
}

}  // namespace

std::string write_ahap(const SoundTrack& track) {
    Json pattern = Json::array();
    bool control_left_on = false;  // a curve of the event before still holds its last value
    const auto& events = track.events;
    for (std::size_t i = 0; i < events.size(); ++i) {
        const auto& event = events[i];
        const double peak = std::max(event.strength_start, event.strength_end);
        const bool ramps = event.strength_start != event.strength_end && peak > 0.0;
        const bool glides = event.pitch_start != event.pitch_end;
        // Split at Apple's 30-second cap; the pieces touch and so read back as tied notes.
        for (double from = 0.0; from < event.duration || from == 0.0; from += ahap_max_event_s) {
            const double length = std::min(ahap_max_event_s, event.duration - from);
            pattern.push_back(Json{{"Event",
                                    {{"Time", event.onset + from},
                                     {"EventType", "HapticContinuous"},
                                     {"EventDuration", length},
                                     {"EventParameters",
                                      {parameter("HapticIntensity", peak),
                                       parameter("HapticSharpness", event.pitch_start)}}}}});
            if (event.duration <= 0.0) {
                break;
            }
        }
        // Curves apply to the whole pattern: each one ends by setting its control back to
        // neutral at the next onset, or, when the next note follows without a gap, the next
        // note starts its own curve.
        const bool next_touches = i + 1 < events.size() && events[i + 1].onset <= event.end();
        const auto finish = [&](std::vector<std::pair<double, double>> points, double neutral) {
            if (i + 1 < events.size() && !next_touches) {
                points.emplace_back(events[i + 1].onset - event.onset, neutral);
            }
            return points;
        };
        if (ramps) {
            pattern.push_back(curve("HapticIntensityControl", event.onset,
                                    finish({{0.0, event.strength_start / peak},
                                            {event.duration, event.strength_end / peak}},
                                           1.0)));
        }
        if (glides) {
            pattern.push_back(curve(
                "HapticSharpnessControl", event.onset,
                finish({{0.0, 0.0}, {event.duration, event.pitch_end - event.pitch_start}}, 0.0)));
        }
        if (control_left_on && !ramps) {
            pattern.push_back(curve("HapticIntensityControl", event.onset, {{0.0, 1.0}}));
        }
        if (control_left_on && !glides) {
            pattern.push_back(curve("HapticSharpnessControl", event.onset, {{0.0, 0.0}}));
        }
        control_left_on = (ramps || glides) && next_touches;
    }
    // The rest at the end: Core Haptics counts a pattern's length to the end of its last event
    // or the start of its last parameter, so a curve that holds the intensity control at
    // neutral, beginning where the piece ends, keeps the period of a pattern played in a loop.
    const double last_end = events.empty() ? 0.0 : events.back().end();
    if (track.duration > last_end + 1e-9) {
        pattern.push_back(curve("HapticIntensityControl", track.duration, {{0.0, 1.0}}));
    }
    Json metadata{{"Project", track.title},
                  {"Description", "exported by vibscore from a vibrotactile score"}};
    if (track.tempo > 0.0) {
        metadata["Tempo"] = track.tempo;  // seconds per quarter note, for importing it back
    }
    Json document{
        {"Version", 1.0}, {"Metadata", std::move(metadata)}, {"Pattern", std::move(pattern)}};
    return document.dump(2) + "\n";
}

ImportedScore read_ahap(std::string_view text, const std::string& file, const ChosenClef& chosen) {
    check_document_size(text, file);
    // Apple's parser takes trailing commas, and Apple's own sample files have them.
    const JsonDocument document(text, file, {.trailing_commas = true});
    DiagnosticSink sink;
    AhapReader reader(document, sink);
    reader.read();
    sink.throw_if_any();
    sort_curves(reader.intensity_curves);
    sort_curves(reader.sharpness_curves);

    // Where the intensity control bends: every curve's start and control point. An event that
    // spans bends keeps them, so its notes can follow the curve rather than one straight ramp.
    std::vector<double> bends;
    for (const auto& curve : reader.intensity_curves) {
        bends.push_back(curve.start);
        for (const auto& point : curve.points) {
            bends.push_back(point.first);
        }
    }
    std::sort(bends.begin(), bends.end());
    bends.erase(std::unique(bends.begin(), bends.end()), bends.end());

    std::vector<double> onsets;
    for (const auto& haptic : reader.events) {
        onsets.push_back(haptic.time);
    }
    std::sort(onsets.begin(), onsets.end());
    std::size_t bent = 0;

    std::vector<SoundEvent> events;
    for (const auto& haptic : reader.events) {
        const auto at = [&](double t, bool at_start) {
            const double intensity =
                haptic.intensity * control_at(reader.intensity_curves, t, at_start, 1.0);
            const double sharpness =
                haptic.sharpness + control_at(reader.sharpness_curves, t, at_start, 0.0);
            return std::make_pair(std::clamp(intensity, 0.0, 1.0), std::clamp(sharpness, 0.0, 1.0));
        };
        SoundEvent event;
        event.onset = haptic.time;
        event.duration = haptic.duration;
        std::tie(event.strength_start, event.pitch_start) = at(haptic.time, true);
        std::tie(event.strength_end, event.pitch_end) =
            haptic.duration > 0.0 ? at(haptic.time + haptic.duration, false)
                                  : std::make_pair(event.strength_start, event.pitch_start);
        // Only while it sounds: one voice, so a later onset ends it (as place_on_grid has it).
        const auto later = std::upper_bound(onsets.begin(), onsets.end(), haptic.time);
        const double sounds_until = later == onsets.end()
                                        ? haptic.time + haptic.duration
                                        : std::min(haptic.time + haptic.duration, *later);
        event.strength_points = bends_within(
            bends, haptic.time, sounds_until, event.strength_start, at(sounds_until, false).first,
            [&](double t, bool at_start) { return at(t, at_start).first; }, bent);
        // Each bend is a note at least: past a score's symbols, refused before any layout (and
        // before events sounding together cost a look at every bend each).
        if (bent > limits::symbols) {
            throw DocumentError({file},
                                "too long for a score: its intensity curves bend more "
                                "than " +
                                    std::to_string(limits::symbols) +
                                    " times within events, each a note; a score holds at "
                                    "most " +
                                    std::to_string(limits::symbols) + " symbols");
        }
        events.push_back(event);
    }
    double total = reader.last_parameter;
    for (const auto& event : events) {
        total = std::max(total, event.end());
    }
    const int strings = static_cast<int>(chosen.clef.strings.size());
    const auto placed = place_on_grid(
        events, total, chosen.clef,
        [&](const SoundEvent& event) { return string_at(event.pitch_start, strings); },
        reader.tempo);
    auto imported = build_score(placed.notes, {{0, placed.tempo}}, placed.total_ticks, chosen,
                                reader.title, file);
    imported.warnings = std::move(reader).warnings();
    for (const auto& shaped : placed.shaped) {
        if (imported.warnings.size() >= limits::diagnostics) {
            break;
        }
        imported.warnings.push_back({{file}, shape_note(shaped, "intensity curve")});
    }
    return imported;
}

}  // namespace vibscore::formats
