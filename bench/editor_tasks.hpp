#pragma once

#include <string>
#include <vector>

#include "client/editor/events.hpp"
#include "client/editor/phrase_book.hpp"

namespace vibscore::bench {

// Issue 26's newcomer tasks, from opening the editor to the last press, counted on the real
// editor (model and six-button scheme) with the planner, split by what the presses did:
//   exp2      Experiment 2's score (thesis Fig. 7.5) from a new score, saved as `exp2`
//   exp2-call the same, "used for incoming call" (save, the event, its proposed name, ok)
//   exp2-tap  the same used for incoming call, its rhythm tapped on Select
//   confirm   a double tap from a new score, saved as `confirm`
//   my-ring   the shipped ringtone with its last note one stronger, saved as `my-ring`, played
// `registry`, when given, is what the editor learns proposals from (each task's score left
// out); `events` the feedback theme's, as vibscore-feedback lists them. Prints a table;
// returns a JSON array.
std::string report_tasks(const std::vector<editor::NamedScore>* registry,
                         const std::vector<editor::EventScore>& events,
                         const std::string& clefs_dir);

// The events of a vibscore-feedback theme file, none assigned.
std::vector<editor::EventScore> theme_events(const std::string& theme_file);

}  // namespace vibscore::bench
