#pragma once

#include <string>

namespace vibscore::drivers {

// A one-line strength meter redrawn in place on a terminal, e.g.
//   sim lra  ▕████████▌           ▏ 0.52  180 Hz
// so a developer without hardware can watch what the actuator would do. Every redraw has the
// same width, so it overwrites the previous one.
//
// On a terminal (a tty whose TERM is not "dumb", at least 3 rows) the meter keeps the bottom row
// for itself: a scrolling region over the rows above takes everything else written there (the
// daemon's log, and the output of other programs sharing the terminal, such as ./dev run's
// `vibscore play`), so no log line ever lands in the middle of the meter. Elsewhere (a pipe, a
// file) it redraws with '\r' and no escape sequences.
class TerminalMeter {
  public:
    enum class Glyphs { ascii, unicode };

    // Draws on fd, which the meter does not own. Draws nothing until the first show().
    TerminalMeter(int fd, std::string label, Glyphs glyphs);
    // Ends the line, if anything was drawn, so the shell prompt does not land on the meter; on a
    // terminal, gives the bottom row back (the whole screen scrolls again) and clears it.
    ~TerminalMeter();

    TerminalMeter(const TerminalMeter&) = delete;
    TerminalMeter& operator=(const TerminalMeter&) = delete;

    // Unicode block glyphs when the locale (LC_ALL, else LC_CTYPE, else LANG) names UTF-8.
    static Glyphs glyphs_for_environment();

    // Redraws with strength 0..1 (clamped) and the frequency in hertz; a negative frequency
    // leaves the frequency column blank (an ERM has no frequency to show).
    void show(double strength, double frequency_hz);

    // The text of one redraw, without the leading '\r'.
    std::string line(double strength, double frequency_hz) const;

    static constexpr int kBarCells = 20;

  private:
    // The terminal's rows when the meter may keep the bottom one (see above), else 0.
    int own_row_terminal_rows() const;

    int fd_;
    std::string label_;
    Glyphs glyphs_;
    bool drawn_ = false;
    int region_rows_ = 0;  // rows of the terminal when the scrolling region was set; 0: none
};

}  // namespace vibscore::drivers
