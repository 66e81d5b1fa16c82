#include "tests/hil/score_expectations.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <thread>

#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "tests/support/support.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {

std::string one_bar_score(const std::string& clef_href, const std::string& notes_xml) {
    return "<VibScore version=\"1.0\"><Title>hil</Title><Clef id=\"c\" href=\"" + clef_href +
           "\"/><Bar clef=\"c\">" + notes_xml + "</Bar></VibScore>";
}

std::vector<render::Cue> expected_drives(const std::string& score_xml,
                                         const render::CueAdaptation& adaptation,
                                         const std::map<std::string, std::string>& own_clefs) {
    const char* clefs = std::getenv("VIBSCORE_CLEFS");
    if (clefs == nullptr) {
        throw std::runtime_error("VIBSCORE_CLEFS is not set: run this through meson test");
    }
    // Every href the score names: its own clef, or the shipped one the registry would find.
    std::map<std::string, std::string> clef_documents;
    const std::string attribute = "href=\"";
    for (auto at = score_xml.find(attribute); at != std::string::npos;
         at = score_xml.find(attribute, at + 1)) {
        const auto begin = at + attribute.size();
        const std::string name = score_xml.substr(begin, score_xml.find('"', begin) - begin);
        if (const auto own = own_clefs.find(name); own != own_clefs.end()) {
            clef_documents[name] = own->second;
            continue;
        }
        const auto text = testing::read_file(std::filesystem::path(clefs) / name);
        if (text.empty()) {
            throw std::runtime_error("no shipped clef " + name + " in " + clefs);
        }
        clef_documents[name] = text;
    }
    const render::Performance performance(testing::bundle_from(score_xml, clef_documents));
    std::vector<render::Cue> drives;
    for (const auto& cue : render::adapt_cues(render::cue_schedule(performance),
                                              performance.duration(), adaptation)) {
        if (cue.kind == render::Cue::Kind::drive) {
            drives.push_back(cue);
        }
    }
    return drives;
}

std::string driver_config(const std::string& driver, const std::string& section_lines) {
    return "driver = " + driver + "\n[" + driver + "]\n" + section_lines;
}

double seconds_between(std::chrono::steady_clock::time_point from,
                       std::chrono::steady_clock::time_point to) {
    return std::chrono::duration<double>(to - from).count();
}

double median(std::vector<double> values) {
    if (values.empty()) {
        return 0.0;
    }
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
    return vibscore::testing::wait_until(condition, timeout, std::chrono::milliseconds(1));
}

}  // namespace vibscore::hil
