// The Standard MIDI File reader and writer, checked against mido (python3-mido), and MIDI import.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "client/formats/midi.hpp"
#include "client/formats/midi_file.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::notes_in;

using ::testing::HasSubstr;

formats::ChosenClef lra_phone() {
    const auto path =
        std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) / "lra-phone.clef.xml";
    return {"lra-phone", load_clef_file(path)};
}

testing::CommandResult mido(const std::string& verb, const std::filesystem::path& file) {
    return testing::run_command({"/usr/bin/python3",
                                 testing::required_env("VIBSCORE_TEST_DATA") + "/midi_fixture.py",
                                 verb, file.string()});
}

std::string error_of(std::string_view bytes) {
    return format(testing::first_diagnostic([&] { formats::midi::read(bytes, "m.mid"); }));
}

std::string header(int format, int tracks, int division) {
    std::string bytes = "MThd";
    bytes += std::string("\0\0\0\x06", 4);
    for (const int value : {format, tracks, division}) {
        bytes += static_cast<char>(value >> 8 & 0xFF);
        bytes += static_cast<char>(value & 0xFF);
    }
    return bytes;
}

std::string track_chunk(const std::string& events) {
    const auto length = events.size();
    std::string bytes = "MTrk";
    for (const int shift : {24, 16, 8, 0}) {
        bytes += static_cast<char>(length >> shift & 0xFF);
    }
    return bytes + events;
}

// A variable-length quantity as a track writes a delta time.
std::string delta(std::uint32_t ticks) {
    std::string bytes(1, static_cast<char>(ticks & 0x7F));
    while ((ticks >>= 7) != 0) {
        bytes.insert(bytes.begin(), static_cast<char>(0x80 | (ticks & 0x7F)));
    }
    return bytes;
}

const std::string kNoteOn("\x90\x3C\x40", 3);
const std::string kNoteOff("\x80\x3C\x40", 3);
const std::string kEndOfTrack("\xFF\x2F\x00", 3);

std::string tempo_event(std::uint32_t micros) {
    return std::string("\x00\xFF\x51\x03", 4) + static_cast<char>(micros >> 16 & 0xFF) +
           static_cast<char>(micros >> 8 & 0xFF) + static_cast<char>(micros & 0xFF);
}

// One note `ticks` long, at `division` ticks a quarter, after `before` (tempo events).
std::string one_note(int division, std::uint32_t ticks, const std::string& before = "") {
    return header(0, 1, division) + track_chunk(before + delta(0) + kNoteOn + delta(ticks) +
                                                kNoteOff + delta(0) + kEndOfTrack);
}

std::string import_error(const std::string& bytes) {
    return format(testing::first_diagnostic(
        [&] { formats::read_midi(bytes, "m.mid", lra_phone(), std::nullopt); }));
}

// The files of issue 27: a few bytes whose delta times claim years. Refused at the byte that
// claims them, before anything is laid out (the old reader laid out 67 million bars first:
// 13.6 GB and more than a minute).
TEST(Midi, AFileOfAFewBytesThatClaimsYearsIsRefusedAtTheByteThatClaimsThem) {
    // 37 bytes: division 1, a note on, a delta of 0x0FFFFFFF ticks, a note off.
    const auto years = one_note(1, 0x0FFF'FFFF);
    ASSERT_EQ(years.size(), 37u);
    EXPECT_EQ(import_error(years),
              "m.mid: byte 26: a note ends 268435455 beats in; a score holds at most 10000 bars "
              "of four beats");
    // 45 bytes: the same at MIDI's fastest tempo (1 us a quarter: 268 s as the file says, but a
    // clef's tempo is 1 ms at least), ending 128 ticks after its note.
    const auto fast =
        header(0, 1, 1) + track_chunk(tempo_event(1) + delta(0) + kNoteOn + delta(0x0FFF'FFFF) +
                                      kNoteOff + delta(128) + kEndOfTrack);
    ASSERT_EQ(fast.size(), 45u);
    EXPECT_EQ(import_error(fast),
              "m.mid: byte 33: a note ends 268435455 beats in; a score holds at most 10000 bars "
              "of four beats");
}

TEST(Midi, ANoteEndingOnTheHourIsReadAndOneEndingA32ndLaterIsRefused) {
    // Division 8: a tick is a 32nd. At the standard's 120 bpm an hour is 7200 quarters.
    EXPECT_EQ(formats::read_midi(one_note(8, 57'600), "m.mid", lra_phone(), std::nullopt)
                  .score.bars.size(),
              1800u);
    EXPECT_EQ(import_error(one_note(8, 57'601)),
              "m.mid: byte 26: a note ends at 3600.062 s; a score lasts at most 3600 s");
}

TEST(Midi, ANoteEndingOnTheLastBeatOfTenThousandBarsIsReadAndOneA32ndLaterIsRefused) {
    // At 20 ms a quarter ten thousand bars last 800 s.
    const auto quick = tempo_event(20'000);
    const auto longest =
        formats::read_midi(one_note(8, 320'000, quick), "m.mid", lra_phone(), std::nullopt);
    EXPECT_EQ(longest.score.bars.size(), 10'000u);
    EXPECT_EQ(import_error(one_note(8, 320'001, quick)),
              "m.mid: byte 33: a note ends 40000.125 beats in; a score holds at most 10000 bars "
              "of four beats");
}

TEST(Midi, ATrackThatEndsPastTheHourIsRefusedAtItsEnd) {
    const auto bytes = header(0, 1, 8) + track_chunk(delta(0) + kNoteOn + delta(8) + kNoteOff +
                                                     delta(57'600) + kEndOfTrack);
    EXPECT_EQ(import_error(bytes),
              "m.mid: byte 30: the track ends at 3600.5 s; a score lasts at most 3600 s");
}

// Issue 27: a ritardando with a tempo change in each of 40 bars was refused as "too long",
// with every number it printed within the limits. It needs 40 clefs; a score declares 32.
TEST(Midi, ARitardandoOfFortyTemposIsRefusedForItsClefsNotItsLength) {
    std::string events;
    for (int bar = 0; bar < 40; ++bar) {
        events += tempo_event(500'000 + 10'000 * static_cast<std::uint32_t>(bar)) + delta(0) +
                  kNoteOn + delta(32) + kNoteOff;
        events += std::string(1, '\0') + std::string("\x90\x3E\x40", 3) + delta(32) +
                  std::string("\x80\x3E\x40", 3);
    }
    const auto bytes = header(0, 1, 16) + track_chunk(events + delta(0) + kEndOfTrack);
    EXPECT_EQ(import_error(bytes),
              "m.mid: too many tempos for a score: 40, each on a clef of its own; a score "
              "declares at most 32 clefs");
}

// Issue 27 item 5: velocity 0 is a note off; the quietest note is velocity 1 however quiet its
// number, and the loudest 127.
TEST(Midi, TheQuietestNoteIsWrittenWithVelocityOneNeverZeroWhichReadsAsANoteOff) {
    const auto bundle = testing::bundle_from(
        testing::one_clef_score(R"(<Bar clef="c"><Note length="quarter" number="1" string="1" />
                                   <Note length="quarter" number="2" string="1" />
                                   <Note length="quarter" number="3" string="1" /></Bar>)"),
        {{"c.xml", testing::sine_clef(0.5, {100}, {0.001, 0.006, 1.0})}});
    const auto file = formats::midi::read(formats::write_midi(bundle), "w.mid");
    std::vector<int> velocities;
    for (const auto& event : file.tracks.at(0).events) {
        if ((event.status & 0xF0) == 0x90) {
            EXPECT_TRUE(event.note_on()) << "a note on of velocity 0 is a note off";
            velocities.push_back(event.data2);
        }
    }
    // 0.001 and 0.006 of the strongest are 0.127 and 0.762 of 127: the floor, and rounded to 1.
    EXPECT_EQ(velocities, (std::vector<int>{1, 1, 127}));
}

TEST(Midi, ImportsATrackMidoWroteWithTheTempoOfItsTempoTrack) {
    testing::TempDir dir;
    const auto file = dir.path() / "melody.mid";
    const auto written = mido("write", file);
    ASSERT_EQ(written.exit_code, 0) << written.err;
    const auto imported =
        formats::read_midi(testing::read_file(file), "melody.mid", lra_phone(), std::nullopt);
    EXPECT_EQ(imported.score.title, "Melody");
    ASSERT_EQ(imported.clefs.size(), 1u);
    EXPECT_EQ(imported.clefs[0].id, "lra-phone-150bpm");
    EXPECT_DOUBLE_EQ(imported.clefs[0].clef.tempo, 0.4);
    ASSERT_EQ(imported.score.bars.size(), 1u);
    const auto& symbols = imported.score.bars[0].symbols;
    ASSERT_EQ(symbols.size(), 4u);
    EXPECT_TRUE(std::holds_alternative<Rest>(symbols[2]));
    const auto notes = notes_in(imported.score);
    ASSERT_EQ(notes.size(), 3u);
    EXPECT_EQ(notes[0].length, Length::quarter);
    EXPECT_EQ(notes[1].length, Length::eighth);  // ended by a note on of velocity 0
    EXPECT_EQ(notes[2].length, Length::quarter_dot);
    // C4, E4, G4 are vibscore's strings 1, 3 and 5.
    EXPECT_EQ(notes[0].string, 1);
    EXPECT_EQ(notes[1].string, 3);
    EXPECT_EQ(notes[2].string, 5);
    // Velocity over 127 is the share of the clef's strongest number 9.
    EXPECT_EQ(notes[0].number, 9);
    EXPECT_EQ(notes[1].number, 4);
    EXPECT_EQ(notes[2].number, 7);
}

TEST(Midi, TrackChoosesTheTrackAndNamesOneThatIsNotThere) {
    testing::TempDir dir;
    const auto file = dir.path() / "melody.mid";
    ASSERT_EQ(mido("write", file).exit_code, 0);
    const auto bytes = testing::read_file(file);
    EXPECT_EQ(notes_in(formats::read_midi(bytes, "m.mid", lra_phone(), 2).score).size(), 3u);
    EXPECT_EQ(format(testing::first_diagnostic(
                  [&] { formats::read_midi(bytes, "m.mid", lra_phone(), 1); })),
              "m.mid: track 1 has no notes");
    EXPECT_EQ(format(testing::first_diagnostic(
                  [&] { formats::read_midi(bytes, "m.mid", lra_phone(), 3); })),
              "m.mid: has 2 tracks; there is no track 3");
}

TEST(Midi, MidoReadsEveryNoteOfEveryShippedScoreAsWritten) {
    testing::TempDir dir;
    int scores = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(testing::required_env("VIBSCORE_CLEFS"))) {
        const auto name = entry.path().filename().string();
        if (!name.ends_with(".score.xml")) {
            continue;
        }
        ++scores;
        const auto bundle = load_score_file(entry.path());
        const auto file = dir.write(name + ".mid", formats::write_midi(bundle));
        const auto dumped = mido("dump", file);
        ASSERT_EQ(dumped.exit_code, 0) << name << ": " << dumped.err;
        // Each note is one MIDI note of its written length, at 480 ticks a quarter.
        std::istringstream lines(dumped.out);
        std::string first;
        std::vector<std::int64_t> lengths;
        while (lines >> first) {
            if (first == "tempo") {
                std::int64_t tick = 0, micros = 0;
                lines >> tick >> micros;
                EXPECT_GT(micros, 0) << name;
                continue;
            }
            std::int64_t start = 0, length = 0;
            int key = 0, velocity = 0;
            lines >> start >> length >> key >> velocity;
            EXPECT_GE(velocity, 1) << name;
            EXPECT_LE(velocity, 127) << name;
            EXPECT_GE(key, formats::midi_string_pitches[0]) << name;
            EXPECT_LE(key, formats::midi_string_pitches[5]) << name;
            lengths.push_back(length);
        }
        const auto notes = notes_in(bundle.score);
        ASSERT_EQ(lengths.size(), notes.size()) << name;
        for (std::size_t i = 0; i < notes.size(); ++i) {
            EXPECT_EQ(lengths[i], std::lround(beats(notes[i].length) * 480)) << name;
        }
    }
    EXPECT_GT(scores, 20);
}

TEST(MidiFile, WritesAndReadsBackEventsWithRunningStatusAndMetaData) {
    formats::midi::File file;
    file.format = 1;
    file.ticks_per_quarter = 96;
    formats::midi::Track track;
    track.events.push_back({0, 0xFF, 0x03, 0, 0, "Lead"});
    track.events.push_back({0, 0x91, 0, 64, 90, ""});
    track.events.push_back({200'000, 0x91, 0, 64, 0, ""});  // a delta of three bytes
    file.tracks = {track, track};
    const auto bytes = formats::midi::write(file);
    const auto read = formats::midi::read(bytes, "m.mid");
    EXPECT_EQ(read.format, 1);
    EXPECT_EQ(read.ticks_per_quarter, 96);
    ASSERT_EQ(read.tracks.size(), 2u);
    const auto& events = read.tracks[1].events;
    ASSERT_EQ(events.size(), 4u);  // with the end of track added
    EXPECT_EQ(events[0].data, "Lead");
    EXPECT_TRUE(events[1].note_on());
    EXPECT_EQ(events[1].channel(), 1);
    EXPECT_EQ(events[2].tick, 200'000);
    EXPECT_TRUE(events[2].note_off());
    EXPECT_EQ(events[3].meta_type, 0x2F);
    // Running status: the second note on leaves out its status byte.
    const std::string running("\x00\x90\x3C\x40\x60\x3C\x00\x00\xFF\x2F\x00", 11);
    const auto parsed = formats::midi::read(header(0, 1, 480) + track_chunk(running), "r.mid");
    ASSERT_EQ(parsed.tracks[0].events.size(), 3u);
    EXPECT_EQ(parsed.tracks[0].events[1].tick, 0x60);
    EXPECT_TRUE(parsed.tracks[0].events[1].note_off());
}

TEST(MidiFile, NamesTheByteWhereTheFileGoesWrong) {
    EXPECT_EQ(error_of("RIFF....MIDI"),
              "m.mid: byte 0: not a Standard MIDI File: it does not begin with MThd");
    EXPECT_EQ(error_of(header(3, 1, 480)), "m.mid: byte 8: format 3 is not 0, 1 or 2");
    EXPECT_EQ(error_of(header(0, 1, 0)),
              "m.mid: byte 12: a time division of 0 ticks per quarter note");
    EXPECT_THAT(error_of(header(0, 2, 480) + track_chunk(std::string("\x00\xFF\x2F\x00", 4))),
                HasSubstr("the header announces 2"));
    // A data byte at the start of a track has no running status to go on.
    EXPECT_EQ(error_of(header(0, 1, 480) + track_chunk(std::string("\x00\x3C\x40", 3))),
              "m.mid: byte 23: a data byte with no running status before it");
    // The chunk claims more bytes than the file has.
    auto cut = header(0, 1, 480) + track_chunk(std::string("\x00\x90\x3C\x40", 4));
    cut.resize(cut.size() - 2);
    EXPECT_THAT(error_of(cut), HasSubstr("m.mid: byte "));
    EXPECT_THAT(error_of(std::string(formats::midi::max_file_bytes + 1, 'x')),
                HasSubstr("larger than the"));
}

}  // namespace
}  // namespace vibscore
