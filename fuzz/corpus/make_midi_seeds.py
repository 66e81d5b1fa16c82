#!/usr/bin/python3
"""Writes the MIDI seed corpus of fuzz/midi_fuzz.cpp into fuzz/corpus/midi/, with mido
(python3-mido) and, for what mido does not write (running status, SMPTE time, sysex), bytes
spelled out here. Run it from anywhere; it replaces the seeds it writes."""
import pathlib
import struct

import mido

HERE = pathlib.Path(__file__).resolve().parent / "midi"


def melody(track, channel=0):
    for key, velocity, length in [(60, 127, 480), (64, 64, 240), (67, 100, 720)]:
        track.append(mido.Message("note_on", channel=channel, note=key, velocity=velocity))
        track.append(mido.Message("note_off", channel=channel, note=key, time=length))


def format0():
    midi = mido.MidiFile(type=0, ticks_per_beat=480)
    track = mido.MidiTrack()
    track.append(mido.MetaMessage("track_name", name="Format 0"))
    track.append(mido.MetaMessage("set_tempo", tempo=mido.bpm2tempo(150)))
    melody(track)
    midi.tracks.append(track)
    midi.save(HERE / "format0.mid")


def format1():
    midi = mido.MidiFile(type=1, ticks_per_beat=96)
    tempo = mido.MidiTrack()
    tempo.append(mido.MetaMessage("set_tempo", tempo=mido.bpm2tempo(90)))
    tempo.append(mido.MetaMessage("set_tempo", tempo=mido.bpm2tempo(180), time=960))
    lead, bass = mido.MidiTrack(), mido.MidiTrack()
    melody(lead)
    melody(bass, channel=1)
    bass.append(mido.Message("program_change", program=33))
    bass.append(mido.Message("pitchwheel", pitch=2000))
    midi.tracks.extend([tempo, lead, bass])
    midi.save(HERE / "format1.mid")


def chunk(kind, payload):
    return kind + struct.pack(">I", len(payload)) + payload


def raw():
    # Running status, a note on of velocity 0 as note off, a sysex, a long delta time.
    events = bytes([0x00, 0x90, 60, 100, 0x83, 0x60, 60, 0, 0x00, 64, 90,
                    0x81, 0x80, 0x00, 64, 0, 0x00, 0xF0, 0x03, 0x7E, 0x09, 0xF7,
                    0x00, 0xFF, 0x2F, 0x00])
    (HERE / "running-status.mid").write_bytes(
        chunk(b"MThd", struct.pack(">HHH", 0, 1, 480)) + chunk(b"MTrk", events))
    # SMPTE time: 25 frames of 40 ticks a second.
    smpte = struct.pack(">HHbB", 0, 1, -25, 40)
    (HERE / "smpte.mid").write_bytes(chunk(b"MThd", smpte) + chunk(b"MTrk", events))


def claims_years():
    """Issue 27: a few bytes whose delta time claims years (0x0FFFFFFF ticks at division 1).
    The import once laid all of it out (13.6 GB, past a minute); it must be refused at once."""
    long_note = bytes([0x00, 0x90, 60, 64, 0xFF, 0xFF, 0xFF, 0x7F, 0x80, 60, 64])
    end = bytes([0x00, 0xFF, 0x2F, 0x00])
    # 37 bytes: a note on, a delta of 0x0FFFFFFF ticks, a note off.
    (HERE / "claims-years.mid").write_bytes(
        chunk(b"MThd", struct.pack(">HHH", 0, 1, 1)) + chunk(b"MTrk", long_note + end))
    # 45 bytes: the same at MIDI's fastest tempo (1 us a quarter), the track ending 128 ticks on.
    fastest = bytes([0x00, 0xFF, 0x51, 0x03, 0x00, 0x00, 0x01])
    (HERE / "claims-years-fast.mid").write_bytes(
        chunk(b"MThd", struct.pack(">HHH", 0, 1, 1))
        + chunk(b"MTrk", fastest + long_note + bytes([0x81, 0x00, 0xFF, 0x2F, 0x00])))


if __name__ == "__main__":
    HERE.mkdir(exist_ok=True)
    format0()
    format1()
    raw()
    claims_years()
