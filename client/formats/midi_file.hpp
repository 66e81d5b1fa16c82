#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

// A Standard MIDI File reader and writer (format 0 and 1), small enough to read in one sitting:
// Debian's libsmf pulls in GLib and reports errors on stderr, and portsmf is unmaintained since
// 2010. Errors name the byte offset where the file goes wrong.
namespace vibscore::formats::midi {

struct Event {
    std::int64_t tick = 0;    // absolute, from the track's start
    std::uint8_t status = 0;  // 0x80..0xEF channel messages; 0xFF meta; 0xF0/0xF7 sysex
    std::uint8_t meta_type = 0;
    std::uint8_t data1 = 0, data2 = 0;
    std::string data;        // meta and sysex payload
    std::size_t offset = 0;  // read: the byte where the event (its delta time) begins

    bool note_on() const { return (status & 0xF0) == 0x90 && data2 > 0; }
    // Note off, or the note on with velocity 0 that running status favours.
    bool note_off() const {
        return (status & 0xF0) == 0x80 || ((status & 0xF0) == 0x90 && data2 == 0);
    }
    int channel() const { return status & 0x0F; }
};

struct Track {
    std::vector<Event> events;
};

struct File {
    int format = 0;
    // Ticks per quarter note; or, for SMPTE time, 0 and ticks_per_second instead.
    int ticks_per_quarter = 480;
    double ticks_per_second = 0.0;
    std::vector<Track> tracks;
};

// Limits that keep a hostile file from taking memory or time.
inline constexpr std::size_t max_file_bytes = 1 << 20;
inline constexpr std::size_t max_tracks = 256;
inline constexpr std::size_t max_events = 200'000;

// Throws DocumentError "FILE: byte N: what is wrong".
File read(std::string_view bytes, const std::string& file);

// Writes a format 0 or 1 file with the given tracks; an end-of-track meta event is added to
// any track that lacks one.
std::string write(const File& file);

}  // namespace vibscore::formats::midi
