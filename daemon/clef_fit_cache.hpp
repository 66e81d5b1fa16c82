#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "score/clef.hpp"

namespace vibscore::daemon {

// The clefs fitted to the declared actuator (vibscored.conf [clefs] fit = auto), kept: fitting
// one is far more work than looking it up, and every Play of a score through an unmapped clef
// would fit it again (issue 30, item 5). An entry is found by the clef's name and its whole
// content (a clef composed again under the same name is another entry) and the declaration it was
// fitted to; a declaration other than the one held (a reload, a calibration applied) empties the
// cache, and so does clear() (a clef composed or deleted, a reload). Bounded: full, it is emptied
// before the next entry. Thread-safe: the workers share one.
class ClefFitCache {
  public:
    static constexpr std::size_t kMaxEntries = 128;

    // `written` fitted to `actuator` with `fit` (render::fit_clef with the fallback of
    // device_clefs.cpp), once per (name, content, declaration). What `fit` throws is not kept.
    Clef fitted(const std::string& name, const Clef& written, const actuator::Declaration& actuator,
                const std::function<Clef(const Clef&)>& fit);
    void clear();
    std::size_t size() const;
    // How many fits were computed (misses), for tests and the log.
    std::size_t fits() const;

  private:
    struct Entry {
        Clef written;
        Clef fitted;
    };
    mutable std::mutex mutex_;
    std::optional<actuator::Declaration> actuator_;
    std::map<std::string, std::vector<Entry>> by_name_;
    std::size_t size_ = 0;
    std::size_t fits_ = 0;
};

}  // namespace vibscore::daemon
