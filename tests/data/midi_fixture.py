#!/usr/bin/python3
"""MIDI fixtures for the tests, through mido (python3-mido), a parser vibscore shares no code with.

  midi_fixture.py write OUT   writes a format 1 file: a tempo track, then a melody at 150 bpm
                              (quarter, eighth, dotted quarter at velocities 127, 64, 100 on
                              pitches 60, 64, 67) with a rest of a quarter before the last note.
  midi_fixture.py dump IN     prints each note of IN as "track start_tick length_ticks key
                              velocity", one a line, and the tempi as "tempo tick microseconds".
"""
import sys

import mido


def write(path):
    tempo = mido.MidiTrack()
    tempo.append(mido.MetaMessage("set_tempo", tempo=mido.bpm2tempo(150), time=0))
    melody = mido.MidiTrack()
    melody.append(mido.MetaMessage("track_name", name="Melody", time=0))
    # (delay before, key, velocity, length) in ticks of 480 a quarter.
    for delay, key, velocity, length in [(0, 60, 127, 480), (0, 64, 64, 240), (480, 67, 100, 720)]:
        melody.append(mido.Message("note_on", note=key, velocity=velocity, time=delay))
        # A note on with velocity 0 ends the second note, as running status favours.
        if key == 64:
            melody.append(mido.Message("note_on", note=key, velocity=0, time=length))
        else:
            melody.append(mido.Message("note_off", note=key, velocity=0, time=length))
    midi = mido.MidiFile(type=1, ticks_per_beat=480)
    midi.tracks.extend([tempo, melody])
    midi.save(path)


def dump(path):
    midi = mido.MidiFile(path)
    for number, track in enumerate(midi.tracks):
        tick = 0
        sounding = {}
        for message in track:
            tick += message.time
            if message.type == "set_tempo":
                print("tempo", tick, message.tempo)
            elif message.type == "note_on" and message.velocity > 0:
                sounding[message.note] = (tick, message.velocity)
            elif message.type in ("note_off", "note_on"):
                start, velocity = sounding.pop(message.note)
                print(number, start, tick - start, message.note, velocity)


if __name__ == "__main__":
    {"write": write, "dump": dump}[sys.argv[1]](sys.argv[2])
