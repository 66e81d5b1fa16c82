#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "daemon/render/cue_adaptation.hpp"
#include "tests/hil/guest_stalls.hpp"

// What the daemon-level hil tests expect of vibscored, worked out with the code the daemon
// itself runs: a test knows each drive's time, strength and frequency without a second copy of
// the rendering rules, and asserts what the backend made of them in the kernel.
namespace vibscore::hil {

// An inline score of one bar on a shipped clef (found in $VIBSCORE_CLEFS by its href).
std::string one_bar_score(const std::string& clef_href, const std::string& notes_xml);

// The drive cues the player sends for `score_xml` to a backend that can do what `adaptation`
// says, in time order (seconds from the start of the playback): the clefs (`own_clefs` by
// href, as composed into the daemon's store, or else the shipped ones), the daemon's default
// note separation, cue_schedule, then adapt_cues.
std::vector<render::Cue> expected_drives(const std::string& score_xml,
                                         const render::CueAdaptation& adaptation,
                                         const std::map<std::string, std::string>& own_clefs = {});

// The configuration lines a DaemonFixture gets to run `driver` with these lines in its
// section; they come after the fixture's own "driver = sim", so they take its place.
std::string driver_config(const std::string& driver, const std::string& section_lines);

// Seconds from `from` to `to` (negative when `to` is earlier).
double seconds_between(std::chrono::steady_clock::time_point from,
                       std::chrono::steady_clock::time_point to);

// The median (the upper one of an even count); 0 for no values.
double median(std::vector<double> values);

// Polls `condition` every millisecond until it holds; false after `timeout`.
bool eventually(const std::function<bool()>& condition,
                std::chrono::milliseconds timeout = std::chrono::seconds(5));

// Tolerance of an onset under TCG, relative to the first onset of the same playback: the
// guest is emulated, and its threads can stall for milliseconds.
constexpr double kOnsetTolerance_s = 0.025;

// kOnsetTolerance_s, and the longest `stalls` saw the whole guest stop while it watched: a
// daemon on time in a guest that was not running is late by that much, through no fault of
// its own.
// (Inline: the integration tests share this file's expectations but not the hil fixtures.)
inline double onset_tolerance_s(const GuestStallMeter& stalls) {
    return kOnsetTolerance_s + stalls.worst_s();
}

}  // namespace vibscore::hil
