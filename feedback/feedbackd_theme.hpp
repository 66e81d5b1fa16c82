#pragma once

#include "feedback/json_fields.hpp"
#include "feedback/theme.hpp"
#include "score/pattern_score.hpp"

// feedbackd's theme JSON (/usr/share/feedbackd/themes/default.json) read as a vibscore theme:
// each VibraRumble and VibraPeriodic entry becomes the pattern feedbackd itself would play
// (feedbackd 0.0.3, fbd-feedback-vibra-rumble.c, fbd-dev-vibra.c); Sound, Led and Dummy
// entries are left out, since vibscore only vibrates.
namespace vibscore::feedback {

// VibraRumble: `count` rumbles of duration / count - pause milliseconds each, every one
// followed by `pause`, at feedbackd's rumble strength (strong motor 0x8000 of 0xffff). When
// nothing is left for the rumble, one rumble of 1000 ms, as feedbackd falls back to.
VibrationPattern rumble_pattern(unsigned duration_ms, unsigned count, unsigned pause_ms);

// VibraPeriodic: `magnitude` (of 0x7fff; 0 means full) for duration_ms, fading in over
// fade_in_time_ms (0: the whole duration) from fade_in_level (0: no fade). feedbackd's 200 ms
// start delay and 10 ms sine period are left out: a memoryless vibra ignores the period, and
// the delay is only a wait.
VibrationPattern periodic_pattern(unsigned duration_ms, unsigned magnitude, unsigned fade_in_level,
                                  unsigned fade_in_time_ms);

// Throws DocumentError "file:line:column: what".
Theme read_feedbackd_theme(const JsonFields& json);

}  // namespace vibscore::feedback
