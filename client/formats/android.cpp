#include "client/formats/android.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "client/formats/grid_fit.hpp"
#include "client/formats/json_reading.hpp"
#include "score/limits.hpp"
#include "score/xml_support.hpp"

namespace vibscore::formats {

namespace {

constexpr int kMaxAmplitude = 255;
// Longest step read: the limit on a score's length.
constexpr long long kMaxStepMs = static_cast<long long>(limits::max_score_seconds * 1000);
// A ramp this short or shorter is an attack, a release or a join between tied notes, not a
// note of its own (vibscore writes 1 ms ones).
constexpr double kShortRampS = 0.0015;

// A score's limits, checked step by step as a waveform or envelope is read: a file whose steps
// pass them is refused at the step that does, before any of it is laid out.
class StepBudget {
  public:
    // The message when this step of `duration_ms` takes the piece past a limit, else empty.
    std::string add(long long duration_ms) {
        if (broken_) {
            return {};
        }
        total_ms_ += duration_ms;
        if (duration_ms > 0 && ++steps_ > limits::symbols) {
            broken_ = true;
            return "too long for a score: more than " + std::to_string(limits::symbols) +
                   " steps; a score holds at most " + std::to_string(limits::symbols) + " symbols";
        }
        if (total_ms_ > kMaxStepMs) {
            broken_ = true;
            return "too long for a score: the pattern reaches " + std::to_string(total_ms_) +
                   " ms at this step; a score lasts at most " + std::to_string(kMaxStepMs) +
                   " ms (" + xml::format_number(limits::max_score_seconds) + " s)";
        }
        return {};
    }

  private:
    long long total_ms_ = 0;
    std::size_t steps_ = 0;
    bool broken_ = false;
};

long long ms(double seconds) {
    return std::llround(seconds * 1000.0);
}

struct Step {
    long long duration_ms = 0;
    int amplitude = 0;
};

// The steps of a waveform: silence up to each note, the note at its own strength, and silence
// to the end of the piece. Times are rounded to whole milliseconds from the start, so rounding
// never builds up.
std::vector<Step> waveform_steps(const SoundTrack& track) {
    std::vector<Step> steps;
    long long now = 0;
    const auto to = [&](long long at, int amplitude) {
        if (at > now) {
            steps.push_back({at - now, amplitude});
            now = at;
        }
    };
    for (const auto& event : track.events) {
        to(ms(event.onset), 0);
        const int amplitude =
            event.strength > 0.0
                ? std::clamp(static_cast<int>(std::lround(event.strength * kMaxAmplitude)), 1,
                             kMaxAmplitude)
                : 0;
        to(ms(event.end()), amplitude);
    }
    to(ms(track.duration), 0);
    return steps;
}

std::vector<SoundEvent> waveform_events(const std::vector<Step>& steps, double& total) {
    std::vector<SoundEvent> events;
    long long now = 0;
    for (const auto& step : steps) {
        if (step.amplitude > 0 && step.duration_ms > 0) {
            SoundEvent event;
            event.onset = now / 1000.0;
            event.duration = step.duration_ms / 1000.0;
            event.strength = event.strength_start = event.strength_end =
                static_cast<double>(step.amplitude) / kMaxAmplitude;
            events.push_back(event);
        }
        now += step.duration_ms;
    }
    total = now / 1000.0;
    return events;
}

ImportedScore waveform_score(const std::vector<Step>& steps, const std::string& file,
                             const ChosenClef& chosen) {
    double total = 0.0;
    const auto events = waveform_events(steps, total);
    const auto placed =
        place_on_grid(events, total, chosen.clef, [](const SoundEvent&) { return 1; });
    return build_score(placed.notes, {{0, placed.tempo}}, placed.total_ticks, chosen, "", file);
}

// An envelope point as read: the level and frequency reached after a ramp of `duration_ms`.
struct ControlPoint {
    double amplitude = 0.0, frequency = 0.0;
    long long duration_ms = 0;
};

struct Envelope {
    double initial_frequency = 0.0;  // 0: the first point's
    std::vector<ControlPoint> points;
};

// Ramps into notes: a ramp between two silent levels is a rest; a short ramp up from silence
// (an attack) or between two sounding levels (a join of tied notes) belongs to the ramp after
// it; a short ramp down to silence (a release) belongs to the rest after it.
std::vector<SoundEvent> envelope_events(const std::vector<Envelope>& envelopes, double& total) {
    struct Ramp {
        double t0, t1, a0, a1, f0, f1;
    };
    std::vector<Ramp> ramps;
    double now = 0.0;
    for (const auto& envelope : envelopes) {
        double level = 0.0;
        double frequency = envelope.initial_frequency > 0.0 ? envelope.initial_frequency
                                                            : envelope.points.front().frequency;
        for (const auto& point : envelope.points) {
            const double end = now + point.duration_ms / 1000.0;
            ramps.push_back({now, end, level, point.amplitude, frequency, point.frequency});
            now = end;
            level = point.amplitude;
            frequency = point.frequency;
        }
    }
    total = now;
    // The writer ends a piece whose last note sounds to its very end with a release, the
    // envelope's way back to silence; it is the note's end, not a longer piece.
    if (!ramps.empty() && ramps.back().a0 > 0.0 && ramps.back().a1 <= 0.0 &&
        ramps.back().t1 - ramps.back().t0 <= kShortRampS) {
        total = ramps.back().t0;
    }
    std::vector<SoundEvent> events;
    for (std::size_t i = 0; i < ramps.size(); ++i) {
        Ramp ramp = ramps[i];
        if (ramp.a0 <= 0.0 && ramp.a1 <= 0.0) {
            continue;
        }
        const bool short_ramp = ramp.t1 - ramp.t0 <= kShortRampS;
        if (short_ramp && ramp.a1 <= 0.0) {
            continue;  // a release
        }
        if (short_ramp && i + 1 < ramps.size()) {
            const Ramp& next = ramps[++i];
            ramp = {ramp.t0, next.t1, ramp.a1, next.a1, ramp.f1, next.f1};
        }
        SoundEvent event;
        event.onset = ramp.t0;
        event.duration = ramp.t1 - ramp.t0;
        event.strength_start = ramp.a0;
        event.strength_end = ramp.a1;
        event.frequency_start = ramp.f0;
        event.frequency_end = ramp.f1;
        events.push_back(event);
    }
    return events;
}

ImportedScore envelope_score(const std::vector<Envelope>& envelopes, const std::string& file,
                             const ChosenClef& chosen) {
    double total = 0.0;
    auto events = envelope_events(envelopes, total);
    // Frequencies to strings: by frequency on a sine clef, by contour on another.
    std::map<double, int> string_of_frequency;
    std::vector<double> frequencies;
    for (const auto& event : events) {
        frequencies.push_back(event.frequency_start);
        frequencies.push_back(event.frequency_end);
    }
    const int strings = static_cast<int>(chosen.clef.strings.size());
    if (chosen.clef.type == ClefType::sine) {
        for (const double frequency : frequencies) {
            string_of_frequency[frequency] = nearest_string(chosen.clef, frequency);
        }
    } else {
        std::vector<double> pitches;
        for (const double frequency : frequencies) {
            pitches.push_back(std::log(frequency));
        }
        const auto mapped = strings_by_contour(pitches, strings);
        for (std::size_t i = 0; i < frequencies.size(); ++i) {
            string_of_frequency[frequencies[i]] = mapped[i];
        }
    }
    for (auto& event : events) {
        event.pitch_start = staff_position(string_of_frequency.at(event.frequency_start));
        event.pitch_end = staff_position(string_of_frequency.at(event.frequency_end));
    }
    const auto placed = place_on_grid(events, total, chosen.clef, [&](const SoundEvent& event) {
        return string_of_frequency.at(event.frequency_start);
    });
    return build_score(placed.notes, {{0, placed.tempo}}, placed.total_ticks, chosen, "", file);
}

class AndroidXmlReader {
  public:
    AndroidXmlReader(const xml::Source& source, DiagnosticSink& sink)
        : source_(source), sink_(sink) {}

    void read() {
        auto root = source_.root();
        const std::string_view name = root.name();
        if (name == "vibration-select") {
            xml::check_attributes(source_, root, {}, sink_);
            root = root.child("vibration-effect");  // the first effect is the one a device plays
            if (!root) {
                report(source_.root(), "<vibration-select> holds no <vibration-effect>");
                return;
            }
        } else if (name != "vibration-effect" && name != "vibration") {
            report(root, "root element is <" + std::string(name) +
                             ">, expected <vibration-effect> or <vibration-select>");
            return;
        }
        xml::check_attributes(source_, root, {}, sink_);
        xml::check_no_text(source_, root, sink_);
        read_effects(root, false);
    }

    std::vector<Step> steps;
    std::vector<Envelope> envelopes;

  private:
    void report(pugi::xml_node at, const std::string& message) {
        sink_.report(source_.where(at), message);
    }

    // `repeated`: inside a <repeating-effect>, which Android does not nest (and so the reading
    // never recurses deeper than that, whatever the nesting of the file).
    void read_effects(pugi::xml_node parent, bool repeated) {
        for (const auto child : parent.children()) {
            if (child.type() != pugi::node_element) {
                continue;
            }
            const std::string_view name = child.name();
            if (name == "waveform-effect") {
                read_waveform(child);
            } else if (name == "waveform-envelope-effect") {
                read_envelope(child);
            } else if (name == "repeating-effect" && repeated) {
                report(child,
                       "a <repeating-effect> inside another; Android repeats one part of "
                       "an effect, once");
            } else if (name == "repeating-effect") {
                xml::check_attributes(source_, child, {}, sink_);
                for (const auto part : child.children()) {
                    if (part.type() != pugi::node_element) {
                        continue;
                    }
                    if (std::string_view(part.name()) == "preamble" ||
                        std::string_view(part.name()) == "repeating") {
                        xml::check_attributes(source_, part, {}, sink_);
                        read_effects(part, true);
                    } else {
                        report(part, "unknown element <" + std::string(part.name()) +
                                         "> in <repeating-effect> (expected <preamble> or "
                                         "<repeating>)");
                    }
                }
            } else if (name == "predefined-effect" || name == "primitive-effect" ||
                       name == "vendor-effect") {
                report(child, "<" + std::string(name) +
                                  "> is a device's own effect with no timing to turn into notes; "
                                  "vibscore reads waveforms and envelopes");
            } else {
                report(child, "unknown element <" + std::string(name) + ">");
            }
            if (!steps.empty() && !envelopes.empty()) {
                report(child, "a waveform and an envelope in one file are not supported");
                return;
            }
        }
    }

    void read_waveform(pugi::xml_node effect) {
        xml::check_attributes(source_, effect, {}, sink_);
        xml::check_no_text(source_, effect, sink_);
        for (const auto child : effect.children()) {
            if (child.type() != pugi::node_element) {
                continue;
            }
            if (std::string_view(child.name()) == "waveform-entry") {
                read_entry(child);
            } else if (std::string_view(child.name()) == "repeating") {
                xml::check_attributes(source_, child, {}, sink_);
                for (const auto entry : child.children("waveform-entry")) {
                    read_entry(entry);
                }
            } else {
                report(child, "unknown element <" + std::string(child.name()) +
                                  "> in <waveform-effect> (expected <waveform-entry> or "
                                  "<repeating>)");
            }
        }
    }

    void read_entry(pugi::xml_node entry) {
        xml::check_attributes(source_, entry, {"durationMs", "amplitude"}, sink_);
        const auto duration =
            xml::read_integer(source_, entry, "durationMs", entry.attribute("durationMs").value(),
                              0, kMaxStepMs, sink_);
        const std::string_view amplitude_text = entry.attribute("amplitude").value();
        std::optional<std::int64_t> amplitude = kMaxAmplitude;
        if (amplitude_text != "default") {
            amplitude = xml::read_integer(source_, entry, "amplitude", amplitude_text, 0,
                                          kMaxAmplitude, sink_);
        }
        if (duration && amplitude) {
            if (const auto broken = budget_.add(*duration); !broken.empty()) {
                report(entry, broken);
            }
            steps.push_back({*duration, static_cast<int>(*amplitude)});
        }
    }

    void read_envelope(pugi::xml_node effect) {
        xml::check_attributes(source_, effect, {"initialFrequencyHz"}, sink_);
        xml::check_no_text(source_, effect, sink_);
        Envelope envelope;
        if (const auto initial = effect.attribute("initialFrequencyHz")) {
            envelope.initial_frequency =
                xml::read_number(source_, effect, "initialFrequencyHz", initial.value(), 1e-3,
                                 limits::max_frequency_hz, sink_)
                    .value_or(0.0);
        }
        for (const auto point : effect.children()) {
            if (point.type() != pugi::node_element) {
                continue;
            }
            if (std::string_view(point.name()) != "control-point") {
                report(point, "unknown element <" + std::string(point.name()) +
                                  "> in <waveform-envelope-effect> (expected <control-point>)");
                continue;
            }
            xml::check_attributes(source_, point, {"amplitude", "frequencyHz", "durationMs"},
                                  sink_);
            const auto amplitude = xml::read_number(
                source_, point, "amplitude", point.attribute("amplitude").value(), 0.0, 1.0, sink_);
            const auto frequency = xml::read_number(source_, point, "frequencyHz",
                                                    point.attribute("frequencyHz").value(), 1e-3,
                                                    limits::max_frequency_hz, sink_);
            const auto duration =
                xml::read_integer(source_, point, "durationMs",
                                  point.attribute("durationMs").value(), 1, kMaxStepMs, sink_);
            if (amplitude && frequency && duration) {
                if (const auto broken = budget_.add(*duration); !broken.empty()) {
                    report(point, broken);
                }
                envelope.points.push_back({*amplitude, *frequency, *duration});
            }
        }
        if (envelope.points.empty()) {
            report(effect, "a <waveform-envelope-effect> needs at least one <control-point>");
            return;
        }
        envelopes.push_back(std::move(envelope));
    }

    const xml::Source& source_;
    DiagnosticSink& sink_;
    StepBudget budget_;
};

}  // namespace

std::string write_android_json(const SoundTrack& track, const AndroidOptions& options) {
    nlohmann::ordered_json timings = nlohmann::ordered_json::array();
    nlohmann::ordered_json amplitudes = nlohmann::ordered_json::array();
    for (const auto& step : waveform_steps(track)) {
        timings.push_back(step.duration_ms);
        amplitudes.push_back(step.amplitude);
    }
    const nlohmann::ordered_json document{
        {"timings", std::move(timings)},
        {"amplitudes", std::move(amplitudes)},
        {"repeat", options.loop ? 0 : -1},
    };
    return document.dump(2) + "\n";
}

std::string write_android_xml(const SoundTrack& track, const AndroidOptions& options) {
    pugi::xml_document document;
    auto waveform = document.append_child("vibration-effect").append_child("waveform-effect");
    auto entries = options.loop ? waveform.append_child("repeating") : waveform;
    for (const auto& step : waveform_steps(track)) {
        auto entry = entries.append_child("waveform-entry");
        entry.append_attribute("durationMs") = static_cast<long long>(step.duration_ms);
        entry.append_attribute("amplitude") = step.amplitude;
    }
    return xml::to_text(document);
}

std::string write_android_envelope(const SoundTrack& track, const AndroidOptions& options) {
    for (const auto& event : track.events) {
        if (event.frequency_start <= 0.0 || event.frequency_end <= 0.0) {
            throw std::invalid_argument(
                "the envelope form needs a frequency for every note; notes on curve or line "
                "clefs have none (use android-xml or android-json)");
        }
    }
    pugi::xml_document document;
    auto effect = document.append_child("vibration-effect");
    if (options.loop) {
        effect = effect.append_child("repeating-effect").append_child("repeating");
    }
    auto envelope = effect.append_child("waveform-envelope-effect");
    if (track.events.empty()) {
        throw std::invalid_argument("the envelope form needs at least one note");
    }
    envelope.append_attribute("initialFrequencyHz") =
        xml::format_number(track.events.front().frequency_start).c_str();
    long long now = 0;
    double level = 0.0;
    double frequency = track.events.front().frequency_start;
    const auto to = [&](double amplitude, double hz, long long at) {
        if (at <= now) {
            return;
        }
        auto point = envelope.append_child("control-point");
        point.append_attribute("amplitude") = xml::format_number(amplitude).c_str();
        point.append_attribute("frequencyHz") = xml::format_number(hz).c_str();
        point.append_attribute("durationMs") = at - now;
        now = at;
        level = amplitude;
        frequency = hz;
    };
    for (const auto& event : track.events) {
        const long long onset = ms(event.onset);
        const long long end = ms(event.end());
        if (onset > now && level > 0.0) {
            to(0.0, frequency, std::min(now + 1, onset));  // release
        }
        to(0.0, frequency, onset);
        // A 1 ms attack (or join from a tied note), then the note's own ramp.
        to(event.strength_start, event.frequency_start, std::min(onset + 1, end));
        to(event.strength_end, event.frequency_end, end);
    }
    if (level > 0.0) {
        to(0.0, frequency, now + 1);
    }
    to(0.0, frequency, ms(track.duration));
    return xml::to_text(document);
}

ImportedScore read_android_json(std::string_view text, const std::string& file,
                                const ChosenClef& chosen) {
    check_document_size(text, file);
    const JsonDocument document(text, file);
    DiagnosticSink sink;
    const JsonReader json(document, sink);
    const auto& root = document.root();
    std::vector<Step> steps;
    if (json.expect(root, JsonValue::Kind::object, "an Android waveform")) {
        json.check_keys(root, {"timings", "amplitudes", "repeat"}, "the waveform");
        const auto* timings = json.member(root, "timings", "the waveform");
        const auto* amplitudes = root.find("amplitudes");
        if (timings != nullptr && json.expect(*timings, JsonValue::Kind::array, "timings")) {
            StepBudget budget;
            for (std::size_t i = 0; i < timings->items.size(); ++i) {
                // Without amplitudes, timings alternate off and on (createWaveform(timings,
                // repeat)).
                const auto timing =
                    json.integer(timings->items[i], "a timing", 0, kMaxStepMs).value_or(0);
                if (const auto broken = budget.add(timing); !broken.empty()) {
                    json.report(timings->items[i], broken);
                }
                steps.push_back({timing, i % 2 == 1 ? kMaxAmplitude : 0});
            }
        }
        if (amplitudes != nullptr &&
            json.expect(*amplitudes, JsonValue::Kind::array, "amplitudes")) {
            if (timings != nullptr && amplitudes->items.size() != timings->items.size()) {
                json.report(*amplitudes,
                            "amplitudes has " + std::to_string(amplitudes->items.size()) +
                                " values for " + std::to_string(steps.size()) + " timings");
            }
            for (std::size_t i = 0; i < amplitudes->items.size() && i < steps.size(); ++i) {
                // -1 is VibrationEffect.DEFAULT_AMPLITUDE: the device's default; read as full.
                const auto amplitude =
                    json.integer(amplitudes->items[i], "an amplitude", -1, kMaxAmplitude);
                steps[i].amplitude =
                    amplitude == -1 ? kMaxAmplitude : static_cast<int>(amplitude.value_or(0));
            }
        }
        if (const auto* repeat = root.find("repeat")) {
            json.integer(*repeat, "repeat", -1,
                         std::max<long long>(-1, static_cast<long long>(steps.size()) - 1));
        }
    }
    sink.throw_if_any();
    return waveform_score(steps, file, chosen);
}

ImportedScore read_android_xml(std::string_view text, const std::string& file,
                               const ChosenClef& chosen) {
    check_document_size(text, file);
    const xml::Source source(text, file);
    DiagnosticSink sink;
    AndroidXmlReader reader(source, sink);
    reader.read();
    sink.throw_if_any();
    if (!reader.envelopes.empty()) {
        return envelope_score(reader.envelopes, file, chosen);
    }
    return waveform_score(reader.steps, file, chosen);
}

}  // namespace vibscore::formats
