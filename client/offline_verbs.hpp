#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "client/clef_search.hpp"

namespace vibscore::client {

// Exit codes shared by every verb.
enum ExitCode : int { exit_ok = 0, exit_failed = 1, exit_usage = 2 };

// `--actuator daemon` (render, check): the score bound to the clefs vibscored plays it through
// (mapped in [clefs], or fitted to the declared actuator with fit = auto), as `vibscore get clef
// NAME --device` gives each, and the words that say which.
struct DeviceBound {
    ScoreBundle bundle;
    std::map<std::string, std::string> names;  // by clef id: "lra-phone (fitted)", "erm-phone"
    std::string said;  // "lra-phone -> lra-phone (fitted)", one entry per declared clef
};
// Throws std::runtime_error when vibscored cannot say, DocumentError when the score's notes do
// not fit a device clef.
using DeviceClefBinder = std::function<DeviceBound(const LoadedScore& written)>;

// vibscore check FILE... [--actuator [FILE]]: validates scores (with their clefs, found by
// `clefs`) and clefs. With a declared actuator, also warns where a score asks what it cannot give
// (render::actuator_warnings); warnings do not fail the check. A name that is not a file is a
// registry score or clef (names_a_file, load_registry_document). With `device_clefs`, scores are
// checked through the clefs vibscored plays them with.
int check_documents(const std::vector<std::string>& files, const ClefSearch& clefs,
                    std::ostream& out, std::ostream& err,
                    const std::optional<actuator::Declaration>& actuator = std::nullopt,
                    const DeviceClefBinder& device_clefs = {});

struct RenderRequest {
    std::string file;
    std::uint32_t rate = 8000;
    std::string out;  // .csv or .wav; empty for none
    bool plot = false;
    int plot_width = 72;
    std::string svg, png;  // the signal and its envelope as a picture; empty for none
    // --actuator [FILE] (an [actuator] section, or the daemon's): --out FILE.csv then has the
    // written strength and the strength that actuator produces without and with compensation
    // (render::actuator_response); --plot draws the three as charts and --svg/--png as a
    // picture (pictures::ResponsePicture) in place of the envelope and the signal.
    std::optional<actuator::Declaration> actuator;
    // --actuator daemon: the clefs vibscored plays the score through, not the written ones.
    DeviceClefBinder device_clefs;
};

// vibscore render FILE|NAME --rate HZ --out OUT.csv|OUT.wav [--plot] [--svg F] [--png F]
int render_document(const RenderRequest& request, const ClefSearch& clefs, std::ostream& out,
                    std::ostream& err);

// What a score holds: title, duration, clefs (with where each came from) and bars (vibscore
// info).
void describe_score(const LoadedScore& loaded, std::ostream& out);

// vibscore info FILE: what a score or clef holds.
int describe_document(const std::string& file, const ClefSearch& clefs, std::ostream& out,
                      std::ostream& err);

}  // namespace vibscore::client
