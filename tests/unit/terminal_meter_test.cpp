// The sim's live meter on a real pseudo-terminal: it keeps the bottom row for itself, so the
// daemon's log and other programs' output scroll above it instead of landing inside it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "common/unique_fd.hpp"
#include "daemon/drivers/terminal_meter.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A pseudo-terminal of `rows` rows: the meter draws on the follower side, the test reads what a
// terminal emulator would receive from the leader side.
class PseudoTerminal {
  public:
    explicit PseudoTerminal(unsigned short rows) {
        int leader = -1, follower = -1;
        winsize size{};
        size.ws_row = rows;
        size.ws_col = 80;
        if (::openpty(&leader, &follower, nullptr, nullptr, &size) != 0) {
            throw std::runtime_error("openpty failed");
        }
        leader_ = UniqueFd(leader);
        follower_ = UniqueFd(follower);
        ::fcntl(leader_.get(), F_SETFL, O_NONBLOCK);
    }
    int follower() const { return follower_.get(); }
    void resize(unsigned short rows) const {
        winsize size{};
        size.ws_row = rows;
        size.ws_col = 80;
        ::ioctl(follower_.get(), TIOCSWINSZ, &size);
    }
    // Everything written so far (the writes are done when it is called: no waiting needed, a
    // pty's buffer holds them).
    std::string read_all() const {
        std::string text;
        char buffer[4096];
        for (;;) {
            const ssize_t got = ::read(leader_.get(), buffer, sizeof buffer);
            if (got <= 0) {
                return text;
            }
            text.append(buffer, static_cast<std::size_t>(got));
        }
    }

  private:
    UniqueFd leader_, follower_;
};

class TerminalMeterOnATerminal : public ::testing::Test {
  protected:
    void SetUp() override {
        const char* term = std::getenv("TERM");
        saved_term_ = term != nullptr ? term : "";
        had_term_ = term != nullptr;
        setenv("TERM", "xterm", 1);
    }
    void TearDown() override {
        if (had_term_) {
            setenv("TERM", saved_term_.c_str(), 1);
        } else {
            unsetenv("TERM");
        }
    }
    std::string saved_term_;
    bool had_term_ = false;
};

TEST_F(TerminalMeterOnATerminal, KeepsTheBottomRowAndLetsEverythingElseScrollAbove) {
    const PseudoTerminal terminal(24);
    {
        TerminalMeter meter(terminal.follower(), "sim lra", TerminalMeter::Glyphs::ascii);
        meter.show(0.5, 180.0);
        const std::string first = terminal.read_all();
        // Rows 1-23 scroll; the meter is drawn on row 24 with the cursor saved and restored, so
        // whatever is written next continues where it was, above the meter.
        EXPECT_THAT(first, HasSubstr("\0337\033[1;23r\0338"));
        EXPECT_THAT(first, HasSubstr("\0337\033[24;1H\033[2Ksim lra  [##########          ] 0.50"));
        EXPECT_THAT(first, Not(HasSubstr("\rsim")));  // not redrawn in place over the log
        meter.show(1.0, 175.0);
        const std::string second = terminal.read_all();
        EXPECT_THAT(second, Not(HasSubstr("r\0338")));  // the region is set once
        EXPECT_THAT(second, HasSubstr("\033[24;1H\033[2Ksim lra  [####################] 1.00"));
    }
    // Gone: the whole screen scrolls again, and the meter's row is cleared.
    EXPECT_THAT(terminal.read_all(), HasSubstr("\033[r\0338\0337\033[24;1H\033[2K\0338"));
}

TEST_F(TerminalMeterOnATerminal, FollowsAResizedTerminal) {
    const PseudoTerminal terminal(24);
    TerminalMeter meter(terminal.follower(), "sim lra", TerminalMeter::Glyphs::ascii);
    meter.show(0.5, 180.0);
    terminal.read_all();
    terminal.resize(40);
    meter.show(0.5, 180.0);
    const std::string text = terminal.read_all();
    EXPECT_THAT(text, HasSubstr("\033[1;39r"));
    EXPECT_THAT(text, HasSubstr("\033[40;1H"));
}

// The edges of "a terminal it can keep a row of": 3 rows is the fewest (one for the meter, two to
// scroll), 2 falls back to redrawing in place; so does TERM=dumb.
TEST_F(TerminalMeterOnATerminal, ThreeRowsAreEnoughTwoAndDumbTerminalsRedrawInPlace) {
    {
        const PseudoTerminal three(3);
        TerminalMeter meter(three.follower(), "sim lra", TerminalMeter::Glyphs::ascii);
        meter.show(0.5, 180.0);
        EXPECT_THAT(three.read_all(), HasSubstr("\033[1;2r"));
    }
    {
        const PseudoTerminal two(2);
        TerminalMeter meter(two.follower(), "sim lra", TerminalMeter::Glyphs::ascii);
        meter.show(0.5, 180.0);
        const std::string text = two.read_all();
        EXPECT_THAT(text, Not(HasSubstr("\033[")));
        EXPECT_THAT(text, HasSubstr("sim lra  [##########          ] 0.50"));
    }
    setenv("TERM", "dumb", 1);
    const PseudoTerminal dumb(24);
    TerminalMeter meter(dumb.follower(), "sim lra", TerminalMeter::Glyphs::ascii);
    meter.show(0.5, 180.0);
    EXPECT_THAT(dumb.read_all(), Not(HasSubstr("\033[")));
}

}  // namespace
}  // namespace vibscore::drivers
