#include "daemon/render/cue_stream.hpp"

namespace vibscore::render {

std::vector<Cue> collect(CueStream& stream) {
    std::vector<Cue> cues;
    while (auto cue = stream.next()) {
        cues.push_back(*cue);
    }
    return cues;
}

}  // namespace vibscore::render
