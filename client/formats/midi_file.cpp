#include "client/formats/midi_file.hpp"

#include <algorithm>

#include "score/document_error.hpp"

namespace vibscore::formats::midi {

namespace {

class ByteReader {
  public:
    ByteReader(std::string_view bytes, std::size_t offset, std::size_t end, const std::string& file)
        : bytes_(bytes), at_(offset), end_(end), file_(file) {}

    [[noreturn]] void fail(const std::string& message, std::size_t at) const {
        throw DocumentError({file_}, "byte " + std::to_string(at) + ": " + message);
    }
    [[noreturn]] void fail(const std::string& message) const { fail(message, at_); }

    std::size_t at() const { return at_; }
    bool done() const { return at_ >= end_; }
    std::uint8_t peek() const {
        if (at_ >= end_) {
            fail("the data ends in the middle of an event");
        }
        return static_cast<std::uint8_t>(bytes_[at_]);
    }
    std::uint8_t byte() {
        const auto value = peek();
        ++at_;
        return value;
    }
    std::uint32_t big_endian(int count) {
        std::uint32_t value = 0;
        for (int i = 0; i < count; ++i) {
            value = value << 8 | byte();
        }
        return value;
    }
    // A variable-length quantity: 7 bits a byte, high bit set on all but the last, at most 4.
    std::uint32_t variable() {
        const auto start = at_;
        std::uint32_t value = 0;
        for (int i = 0; i < 4; ++i) {
            const auto b = byte();
            value = value << 7 | (b & 0x7F);
            if ((b & 0x80) == 0) {
                return value;
            }
        }
        fail("a variable-length number longer than 4 bytes", start);
    }
    std::string take(std::uint32_t count) {
        if (count > end_ - at_) {
            fail("a length of " + std::to_string(count) + " bytes runs past the end of its chunk");
        }
        std::string data(bytes_.substr(at_, count));
        at_ += count;
        return data;
    }
    std::uint8_t data_byte() {
        const auto start = at_;
        const auto value = byte();
        if (value & 0x80) {
            fail("expected a data byte (below 0x80), found a status byte", start);
        }
        return value;
    }

  private:
    std::string_view bytes_;
    std::size_t at_;
    std::size_t end_;
    const std::string& file_;
};

int data_bytes_of(std::uint8_t status) {
    switch (status & 0xF0) {
        case 0xC0:
        case 0xD0:
            return 1;
        default:
            return 2;
    }
}

Track read_track(ByteReader& reader, std::size_t& events_read) {
    Track track;
    std::int64_t tick = 0;
    std::uint8_t running = 0;
    bool ended = false;
    while (!reader.done() && !ended) {
        Event event;
        event.offset = reader.at();
        tick += reader.variable();
        event.tick = tick;
        const auto start = reader.at();
        std::uint8_t status = reader.peek();
        if (status & 0x80) {
            reader.byte();
        } else if (running == 0) {
            reader.fail("a data byte with no running status before it", start);
        } else {
            status = running;
        }
        event.status = status;
        if (status == 0xFF) {
            event.meta_type = reader.data_byte();
            event.data = reader.take(reader.variable());
            ended = event.meta_type == 0x2F;
            running = 0;
        } else if (status == 0xF0 || status == 0xF7) {
            event.data = reader.take(reader.variable());
            running = 0;
        } else if (status >= 0xF1) {
            reader.fail("system message " + std::to_string(status) + " has no place in a file",
                        start);
        } else {
            running = status;
            event.data1 = reader.data_byte();
            if (data_bytes_of(status) == 2) {
                event.data2 = reader.data_byte();
            }
        }
        if (++events_read > max_events) {
            reader.fail("more than " + std::to_string(max_events) + " events");
        }
        track.events.push_back(std::move(event));
    }
    return track;
}

void put_big_endian(std::string& out, std::uint32_t value, int count) {
    for (int i = count - 1; i >= 0; --i) {
        out += static_cast<char>((value >> (8 * i)) & 0xFF);
    }
}

void put_variable(std::string& out, std::uint32_t value) {
    std::string bytes(1, static_cast<char>(value & 0x7F));
    while ((value >>= 7) != 0) {
        bytes.insert(bytes.begin(), static_cast<char>(0x80 | (value & 0x7F)));
    }
    out += bytes;
}

}  // namespace

File read(std::string_view bytes, const std::string& file) {
    if (bytes.size() > max_file_bytes) {
        throw DocumentError({file}, "larger than the " + std::to_string(max_file_bytes) +
                                        "-byte limit for a MIDI file");
    }
    ByteReader header(bytes, 0, bytes.size(), file);
    if (bytes.substr(0, 4) != "MThd") {
        header.fail("not a Standard MIDI File: it does not begin with MThd", 0);
    }
    header.take(4);
    const auto header_length = header.big_endian(4);
    if (header_length < 6) {
        header.fail(
            "the MThd header is " + std::to_string(header_length) + " bytes long; it needs 6", 4);
    }
    File midi;
    midi.format = static_cast<int>(header.big_endian(2));
    const auto track_count = header.big_endian(2);
    const auto division = header.big_endian(2);
    if (midi.format > 2) {
        header.fail("format " + std::to_string(midi.format) + " is not 0, 1 or 2", 8);
    }
    if (division & 0x8000) {
        // SMPTE: frames per second (as a negative byte) times ticks per frame.
        const int frames = 256 - static_cast<int>(division >> 8);
        const int per_frame = static_cast<int>(division & 0xFF);
        if (frames <= 0 || per_frame == 0) {
            header.fail("an SMPTE time division with no ticks", 12);
        }
        midi.ticks_per_quarter = 0;
        midi.ticks_per_second = (frames == 29 ? 29.97 : frames) * per_frame;
    } else if (division == 0) {
        header.fail("a time division of 0 ticks per quarter note", 12);
    } else {
        midi.ticks_per_quarter = static_cast<int>(division);
    }
    if (track_count > max_tracks) {
        header.fail("more than " + std::to_string(max_tracks) + " tracks", 10);
    }
    std::size_t at = 8 + header_length;
    std::size_t events_read = 0;
    while (midi.tracks.size() < track_count) {
        if (at + 8 > bytes.size()) {
            header.fail("the header announces " + std::to_string(track_count) +
                            " tracks; the file holds " + std::to_string(midi.tracks.size()),
                        std::min(at, bytes.size()));
        }
        ByteReader chunk(bytes, at + 4, at + 8, file);
        const auto length = chunk.big_endian(4);
        const std::size_t body = at + 8;
        if (length > bytes.size() - body) {
            chunk.fail("a chunk of " + std::to_string(length) +
                           " bytes runs past the end of "
                           "the file",
                       at + 4);
        }
        if (bytes.substr(at, 4) == "MTrk") {
            ByteReader reader(bytes, body, body + length, file);
            midi.tracks.push_back(read_track(reader, events_read));
        }  // other chunk types are skipped, as the standard asks
        at = body + length;
    }
    return midi;
}

std::string write(const File& file) {
    std::string out = "MThd";
    put_big_endian(out, 6, 4);
    put_big_endian(out, static_cast<std::uint32_t>(file.format), 2);
    put_big_endian(out, static_cast<std::uint32_t>(file.tracks.size()), 2);
    put_big_endian(out, static_cast<std::uint32_t>(file.ticks_per_quarter), 2);
    for (const auto& track : file.tracks) {
        std::string body;
        std::int64_t tick = 0;
        bool ended = false;
        for (const auto& event : track.events) {
            put_variable(body, static_cast<std::uint32_t>(event.tick - tick));
            tick = event.tick;
            body += static_cast<char>(event.status);
            if (event.status == 0xFF) {
                body += static_cast<char>(event.meta_type);
                put_variable(body, static_cast<std::uint32_t>(event.data.size()));
                body += event.data;
                ended = event.meta_type == 0x2F;
            } else if (event.status == 0xF0 || event.status == 0xF7) {
                put_variable(body, static_cast<std::uint32_t>(event.data.size()));
                body += event.data;
            } else {
                body += static_cast<char>(event.data1);
                if (data_bytes_of(event.status) == 2) {
                    body += static_cast<char>(event.data2);
                }
            }
        }
        if (!ended) {
            body += std::string("\x00\xFF\x2F\x00", 4);
        }
        out += "MTrk";
        put_big_endian(out, static_cast<std::uint32_t>(body.size()), 4);
        out += body;
    }
    return out;
}

}  // namespace vibscore::formats::midi
