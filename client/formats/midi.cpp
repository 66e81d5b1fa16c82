#include "client/formats/midi.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "score/limits.hpp"
#include "score/xml_support.hpp"

#include "client/formats/grid_fit.hpp"
#include "client/formats/midi_file.hpp"
#include "client/formats/sound_events.hpp"
#include "daemon/render/performance.hpp"

namespace vibscore::formats {

namespace {

constexpr int kTicksPerQuarter = 480;
constexpr std::uint32_t kDefaultMicrosPerQuarter = 500'000;  // 120 bpm, the standard's default

midi::Event meta(std::int64_t tick, std::uint8_t type, std::string data) {
    midi::Event event;
    event.tick = tick;
    event.status = 0xFF;
    event.meta_type = type;
    event.data = std::move(data);
    return event;
}

std::string tempo_bytes(double tempo) {
    const auto micros = static_cast<std::uint32_t>(std::lround(tempo * 1e6));
    return {static_cast<char>(micros >> 16 & 0xFF), static_cast<char>(micros >> 8 & 0xFF),
            static_cast<char>(micros & 0xFF)};
}

struct MidiNote {
    std::int64_t on = 0, off = 0;  // ticks
    int pitch = 0, velocity = 0;
    std::size_t off_offset = 0;  // the byte of the event that ends it
};

std::vector<MidiNote> notes_of(const midi::Track& track) {
    std::vector<MidiNote> notes;
    std::map<std::pair<int, int>, std::vector<std::size_t>> sounding;  // channel, key
    std::int64_t last_tick = 0;
    for (const auto& event : track.events) {
        last_tick = std::max(last_tick, event.tick);
        const auto key = std::make_pair(event.channel(), static_cast<int>(event.data1));
        if (event.status < 0xF0 && event.note_on()) {
            sounding[key].push_back(notes.size());
            notes.push_back({event.tick, event.tick, event.data1, event.data2, event.offset});
        } else if (event.status < 0xF0 && event.note_off()) {
            auto& open = sounding[key];
            if (!open.empty()) {
                notes[open.front()].off = event.tick;
                notes[open.front()].off_offset = event.offset;
                open.erase(open.begin());
            }
        }
    }
    for (const auto& [key, open] : sounding) {
        for (const auto index : open) {
            notes[index].off = last_tick;  // never released: it lasts to the track's end
            notes[index].off_offset = track.events.back().offset;
        }
    }
    // One voice: of notes starting together the highest is the melody.
    std::stable_sort(notes.begin(), notes.end(), [](const MidiNote& a, const MidiNote& b) {
        return a.on != b.on ? a.on < b.on : a.pitch < b.pitch;
    });
    return notes;
}

std::int64_t track_end(const midi::Track& track) {
    return track.events.empty() ? 0 : track.events.back().tick;
}

std::size_t track_end_offset(const midi::Track& track) {
    return track.events.empty() ? 0 : track.events.back().offset;
}

[[noreturn]] void refuse_at(const std::string& file, std::size_t offset, const std::string& what) {
    throw DocumentError({file}, "byte " + std::to_string(offset) + ": " + what);
}

// A note or track that ends past what a score can hold is refused at its byte before anything
// is laid out: a few bytes of delta time can claim years.
void check_end(const std::string& file, std::size_t offset, const std::string& what,
               std::int64_t grid_tick, const std::vector<TempoChange>& tempi) {
    if (grid_tick > max_import_ticks) {
        refuse_at(file, offset,
                  what + " ends " +
                      xml::format_number(static_cast<double>(grid_tick) / ticks_per_quarter) +
                      " beats in; a score holds at most " + std::to_string(limits::bars) +
                      " bars of four beats");
    }
    const double seconds = seconds_at(tempi, grid_tick);
    if (past_the_hour(seconds)) {
        refuse_at(file, offset,
                  what + " ends at " + seconds_text(seconds) + "; a score lasts at most " +
                      seconds_text(limits::max_score_seconds));
    }
}

void check_end_seconds(const std::string& file, std::size_t offset, const std::string& what,
                       double seconds) {
    if (past_the_hour(seconds)) {
        refuse_at(file, offset,
                  what + " ends at " + seconds_text(seconds) + "; a score lasts at most " +
                      seconds_text(limits::max_score_seconds));
    }
}

std::string track_name(const midi::Track& track) {
    for (const auto& event : track.events) {
        if (event.status == 0xFF && event.meta_type == 0x03) {
            return event.data;
        }
    }
    return "";
}

std::vector<int> strings_of(const std::vector<MidiNote>& notes, int strings) {
    const std::set<int> ours(std::begin(midi_string_pitches), std::end(midi_string_pitches));
    std::vector<double> pitches;
    bool all_ours = true;
    for (const auto& note : notes) {
        pitches.push_back(note.pitch);
        all_ours = all_ours && ours.contains(note.pitch);
    }
    if (!all_ours) {
        return strings_by_contour(pitches, strings);
    }
    std::vector<int> result;
    for (const auto& note : notes) {
        const auto index =
            std::find(std::begin(midi_string_pitches), std::end(midi_string_pitches), note.pitch) -
            std::begin(midi_string_pitches);
        result.push_back(std::min(static_cast<int>(index) + 1, strings));
    }
    return result;
}

}  // namespace

std::string write_midi(const ScoreBundle& bundle) {
    midi::Track track;
    track.events.push_back(meta(0, 0x03, bundle.score.title));
    const double peak = strongest_number(bundle);
    std::int64_t tick = 0;
    double tempo = 0.0;
    for (const auto& bar : bundle.score.bars) {
        const Clef& clef = bundle.clef_of(bar);
        if (clef.tempo != tempo) {
            tempo = clef.tempo;
            track.events.push_back(meta(tick, 0x51, tempo_bytes(tempo)));
        }
        for (const auto& symbol : bar.symbols) {
            const auto* note = std::get_if<Note>(&symbol);
            const auto* rest = std::get_if<Rest>(&symbol);
            if (note == nullptr && rest == nullptr) {
                continue;
            }
            const auto length = static_cast<std::int64_t>(std::lround(
                beats(note != nullptr ? note->length : rest->length) * kTicksPerQuarter));
            if (note != nullptr) {
                const double amplitude =
                    clef.numbers.at(static_cast<std::size_t>(note->number - 1));
                const int velocity = std::clamp(
                    static_cast<int>(std::lround(peak > 0.0 ? amplitude / peak * 127 : 0.0)), 1,
                    127);
                const auto pitch = static_cast<std::uint8_t>(
                    midi_string_pitches[std::clamp(note->string, 1, 6) - 1]);
                midi::Event on;
                on.tick = tick;
                on.status = 0x90;
                on.data1 = pitch;
                on.data2 = static_cast<std::uint8_t>(velocity);
                midi::Event off = on;
                off.tick = tick + length;
                off.status = 0x80;
                off.data2 = 0x40;
                track.events.push_back(on);
                track.events.push_back(off);
            }
            tick += length;
        }
    }
    track.events.push_back(meta(tick, 0x2F, ""));
    midi::File file;
    file.format = 0;
    file.ticks_per_quarter = kTicksPerQuarter;
    file.tracks.push_back(std::move(track));
    return midi::write(file);
}

ImportedScore read_midi(std::string_view bytes, const std::string& file, const ChosenClef& chosen,
                        std::optional<int> track_number) {
    const auto midi = midi::read(bytes, file);
    std::size_t chosen_track = 0;
    if (track_number) {
        if (*track_number < 1 || static_cast<std::size_t>(*track_number) > midi.tracks.size()) {
            throw DocumentError({file}, "has " + std::to_string(midi.tracks.size()) +
                                            " tracks; there is no track " +
                                            std::to_string(*track_number));
        }
        chosen_track = static_cast<std::size_t>(*track_number - 1);
    } else {
        while (chosen_track < midi.tracks.size() && notes_of(midi.tracks[chosen_track]).empty()) {
            ++chosen_track;
        }
        if (chosen_track == midi.tracks.size()) {
            throw DocumentError({file}, "has no notes in any of its " +
                                            std::to_string(midi.tracks.size()) + " tracks");
        }
    }
    const auto& track = midi.tracks[chosen_track];
    const auto notes = notes_of(track);
    if (notes.empty()) {
        throw DocumentError({file}, "track " + std::to_string(chosen_track + 1) + " has no notes");
    }
    std::string title = track_name(track);
    if (title.empty() && !midi.tracks.empty()) {
        title = track_name(midi.tracks.front());
    }
    const int strings = static_cast<int>(chosen.clef.strings.size());
    const auto string_list = strings_of(notes, strings);

    if (midi.ticks_per_quarter == 0) {
        // SMPTE time has no beats: place the notes by their times, as for AHAP.
        for (const auto& note : notes) {
            check_end_seconds(file, note.off_offset, "a note",
                              static_cast<double>(note.off) / midi.ticks_per_second);
        }
        check_end_seconds(file, track_end_offset(track), "the track",
                          static_cast<double>(track_end(track)) / midi.ticks_per_second);
        std::vector<SoundEvent> events;
        for (std::size_t i = 0; i < notes.size(); ++i) {
            SoundEvent event;
            event.onset = notes[i].on / midi.ticks_per_second;
            event.duration = (notes[i].off - notes[i].on) / midi.ticks_per_second;
            event.strength = event.strength_start = event.strength_end = notes[i].velocity / 127.0;
            event.pitch_start = event.pitch_end = staff_position(string_list[i]);
            events.push_back(event);
        }
        const auto placed = place_on_grid(
            events, track_end(track) / midi.ticks_per_second, chosen.clef,
            [&](const SoundEvent& event) { return string_at(event.pitch_start, strings); });
        return build_score(placed.notes, {{0, placed.tempo}}, placed.total_ticks, chosen, title,
                           file);
    }

    const auto grid = [&](std::int64_t tick) {
        return static_cast<std::int64_t>(
            std::llround(static_cast<double>(tick) * ticks_per_quarter / midi.ticks_per_quarter));
    };
    std::vector<TempoChange> tempi{{0, kDefaultMicrosPerQuarter / 1e6}};
    for (const auto& each : midi.tracks) {
        for (const auto& event : each.events) {
            if (event.status == 0xFF && event.meta_type == 0x51 && event.data.size() == 3) {
                const auto micros =
                    static_cast<std::uint32_t>(static_cast<std::uint8_t>(event.data[0]) << 16 |
                                               static_cast<std::uint8_t>(event.data[1]) << 8 |
                                               static_cast<std::uint8_t>(event.data[2]));
                if (micros > 0) {
                    tempi.push_back({grid(event.tick), micros / 1e6});
                }
            }
        }
    }
    std::stable_sort(tempi.begin(), tempi.end(),
                     [](const TempoChange& a, const TempoChange& b) { return a.at < b.at; });
    // At one tick the last tempo set counts.
    std::vector<TempoChange> settled;
    for (const auto& change : tempi) {
        if (!settled.empty() && settled.back().at == change.at) {
            settled.back() = change;
        } else if (settled.empty() || settled.back().tempo != change.tempo) {
            settled.push_back(change);
        }
    }

    for (const auto& note : notes) {
        check_end(file, note.off_offset, "a note", grid(note.off), settled);
    }
    check_end(file, track_end_offset(track), "the track", grid(track_end(track)), settled);

    std::vector<GridNote> grid_notes;
    for (std::size_t i = 0; i < notes.size(); ++i) {
        GridNote note;
        note.start = grid(notes[i].on);
        note.length = std::max<std::int64_t>(1, grid(notes[i].off) - note.start);
        note.string = string_list[i];
        note.number = nearest_number(chosen.clef, notes[i].velocity / 127.0);
        grid_notes.push_back(note);
    }
    return build_score(grid_notes, settled, grid(track_end(track)), chosen, title, file);
}

}  // namespace vibscore::formats
