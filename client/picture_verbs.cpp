#include "client/picture_verbs.hpp"

#include "client/editor/daemon_link.hpp"
#include "client/editor/verbs.hpp"
#include "client/offline_verbs.hpp"
#include "client/pictures/staff_picture.hpp"
#include "score/document_error.hpp"

namespace vibscore::client {

int show_picture(const std::string& score, const std::string& svg, const std::string& png,
                 std::ostream& out, std::ostream& err) {
    try {
        for (const auto& path : {svg, png}) {
            if (!path.empty()) {
                pictures::picture_format_for(path);
            }
        }
    } catch (const std::invalid_argument& error) {
        err << "show: " << error.what() << "\n";
        return exit_usage;
    }
    try {
        const Score shown = editor::read_score_to_show(score);
        const pictures::StaffPicture picture(shown);
        for (const auto& path : {svg, png}) {
            if (!path.empty()) {
                pictures::write_picture(picture, path);
                out << "wrote " << path << " (" << picture.width() << "x" << picture.height()
                    << ")\n";
            }
        }
        return exit_ok;
    } catch (const DocumentError& error) {
        err << error.what() << "\n";
    } catch (const editor::DaemonError& error) {
        err << "vibscore: " << error.what() << "\n";
    } catch (const std::exception& error) {
        err << "show: " << error.what() << "\n";
    }
    return exit_failed;
}

}  // namespace vibscore::client
