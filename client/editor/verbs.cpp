#include "client/editor/verbs.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "client/editor/daemon_link.hpp"
#include "client/editor/documents.hpp"
#include "client/editor/staff_text.hpp"
#include "score/document_error.hpp"
#include "score/score_xml.hpp"

namespace vibscore::editor {

namespace {

int terminal_width() {
    winsize size{};
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) {
        return size.ws_col;
    }
    if (const char* columns = std::getenv("COLUMNS")) {
        if (const int width = std::atoi(columns); width > 0) {
            return width;
        }
    }
    return 80;
}

bool colour_terminal() {
    const char* term = std::getenv("TERM");
    return isatty(STDOUT_FILENO) && std::getenv("NO_COLOR") == nullptr && term != nullptr &&
           std::strcmp(term, "dumb") != 0;
}

}  // namespace

Score read_score_to_show(const std::string& score) {
    const auto source = classify_source(score);
    if (source.kind == ScoreSource::Kind::file) {
        return read_score_file(source.name);
    }
    DaemonLink daemon;
    return read_score(daemon.get("score", source.name), source.name).score;
}

int show_score(const ShowRequest& request, std::ostream& out, std::ostream& err) {
    Score score;
    try {
        score = read_score_to_show(request.score);
    } catch (const DocumentError& error) {
        err << error.what() << "\n";
        return 1;
    } catch (const DaemonError& error) {
        err << "vibscore: " << error.what() << "\n";
        return 1;
    }
    client::StaffTextOptions options;
    options.width = request.width > 0 ? request.width : terminal_width();
    options.colour = request.colour || colour_terminal();
    client::print_staff(out, score, options);
    return 0;
}

}  // namespace vibscore::editor
