// The verbs of `vibscore`, one record each: name, one-line help, and the function that declares
// its arguments and options and makes its handler (verb_files.cpp, verb_device.cpp).
#include "client/verb_table.hpp"

#include "client/verb_declare.hpp"

namespace vibscore::client {

const std::vector<Verb>& verbs() {
    static const std::vector<Verb> table = {
        {"check",
         "Validate scores (with the clefs they name) and clefs; list every problem.",
         declare_check,
         {"*.xml..."}},
        {"render",
         "Render a score's drive signal (clef units) to CSV or WAV, or plot it.",
         declare_render,
         {"*.xml..."}},
        {"convert",
         "Convert a score to AHAP, Android JSON or XML, or MIDI; or AHAP, Android, RTTTL or MIDI "
         "to a score (docs/formats.md says what each format keeps).",
         declare_convert,
         {"*.@(xml|ahap|json|rtttl|rtx|mid|midi)", "*"}},
        {"clef",
         "Work on clefs: fit one to the actuator.",
         nullptr,
         {},
         {{"fit",
           "Write a device clef for the declared actuator from a written clef: strings where it "
           "plays them at full strength (or roughness), numbers keeping their strengths, shapes "
           "it cannot follow smoothed (docs/clefs.md). What changed goes to standard error.",
           declare_clef_fit,
           {"@clefs,*.xml"}}}},
        {"info",
         "Show a score's title, duration, bars and clefs, or a clef's mapping; for a registry "
         "score, also the clef each bar plays through on this device (asks vibscored).",
         declare_info,
         {"*.xml..."}},
        {"play",
         "Play a registry score, or a score file, on the device (through vibscored).",
         declare_play,
         {"@scores,*.xml"}},
        {"stop", "Stop a playback (default: all of yours).", declare_stop},
        {"list", "List the registry's scores or clefs.", declare_list, {"scores,clefs"}},
        {"get", "Print a registry score or clef.", declare_get, {"score,clef", "@kind"}},
        {"compose",
         "Store a score or clef file in the registry (polkit: org.vibscore.compose; without "
         "polkit, root and group vibscore).",
         declare_compose,
         {"", "*.xml"}},
        {"delete",
         "Delete a stored score or clef (polkit: org.vibscore.compose).",
         declare_delete,
         {"score,clef", "@kind"}},
        {"drivers", "List the actuator backends vibscored offers (* in use).", declare_drivers},
        {"driver",
         "Show the actuator backend in use and why (driver = auto: what it found), or switch to "
         "another (polkit: org.vibscore.manage; without polkit, root and group vibscore; its "
         "settings come from vibscored.conf).",
         declare_driver,
         {"@drivers"}},
        {"show",
         "Draw a registry score or a score file as staff notation; with --svg or --png, a "
         "clef's strings and numbers too.",
         declare_show,
         {"@scores,*.xml"}},
        {"assign",
         "Choose the registry score a feedback event plays for you (vibscore-feedback; "
         "docs/feedbackd.md): EVENT SCORE, EVENT --default, or --list.",
         declare_assign,
         {"@events", "@scores"}},
        {"calibrate",
         "Measure the actuator with the device's accelerometer: vibscored plays a short probe "
         "and estimates the [actuator] numbers (--apply: use them from now on; polkit: "
         "org.vibscore.manage). Offline, for any recorder: --plan writes the probe, --estimate "
         "reads a recording of it. Exit 1 when the estimate is not trusted.",
         declare_calibrate,
         // No argument of its own: the second file of --estimate PLAN.csv ACCEL.csv.
         {"*.csv..."}},
        {"edit",
         "Compose in the terminal, by keyboard or six buttons (docs/editor.md).",
         declare_edit,
         {"@scores,*.xml"},
         {},
         "Six buttons (Up Down Left Right Select Back; arrows, Enter, Escape on a keyboard):\n"
         "  the status line names what each does now. Back gives the other choices,\n"
         "  Back, Select the menu: tap a rhythm (t), bar clef (k), edit clefs (K: a clef's\n"
         "  frequencies, amplitudes, tempo and points, heard as they change, saved under a\n"
         "  new name), save, save as. Saving a new score first asks 'use for ...': an event\n"
         "  of the feedback theme (incoming call, new message, ...) then plays it for this\n"
         "  user (as 'vibscore assign' does).\n"
         "Keys: 1-9 note, 0 rest, Space play, Ctrl+S save, Ctrl+Z undo, q quit."},
    };
    return table;
}

}  // namespace vibscore::client
