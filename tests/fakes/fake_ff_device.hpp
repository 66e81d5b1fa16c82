#pragma once

#include <linux/input.h>

#include <cstdint>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "daemon/drivers/evdev_actuator.hpp"
#include "daemon/drivers/ff_device.hpp"

namespace vibscore::testing {

// One input event, without the timestamp nobody sets.
struct WrittenEvent {
    std::uint16_t type;
    std::uint16_t code;
    std::int32_t value;
    bool operator==(const WrittenEvent&) const = default;
};

std::ostream& operator<<(std::ostream& out, const WrittenEvent& event);

// A call the backend made on a fake device, in order.
struct FfCall {
    enum class Kind { upload, erase, write } kind;
    ff_effect effect{};                // upload: as the kernel received it (id -1: allocate)
    int id = -1;                       // upload: the id it got; erase: the id erased
    std::vector<WrittenEvent> events;  // write: all events of the one write() call
    unsigned generation = 0;           // which opening of the device the call went to
};

// The kernel side of the fake: a device that holds `effect_slots` effects, can be unplugged and
// plugged in again, and records every call made on any opening of it.
struct FakeFfKernel {
    std::string path = "/dev/input/event5";
    drivers::FfFeatures features{
        .periodic = true, .sine = true, .square = true, .gain = true, .effect_slots = 16};
    bool present = true;
    unsigned generation = 1;  // bumped by unplug(): older openings are dead
    int opens = 0;
    int fail_next_errno = 0;  // the next call fails with this errno, once
    std::vector<FfCall> calls;
    std::map<int, std::uint16_t> live;  // uploaded, not erased: id -> type
    int next_id = 0;

    void unplug() {
        present = false;
        ++generation;
        live.clear();
    }

    std::vector<FfCall> of(FfCall::Kind kind) const {
        std::vector<FfCall> found;
        for (const auto& call : calls) {
            if (call.kind == kind) {
                found.push_back(call);
            }
        }
        return found;
    }
    std::vector<FfCall> uploads() const { return of(FfCall::Kind::upload); }
    std::vector<FfCall> writes() const { return of(FfCall::Kind::write); }
    std::vector<int> erased() const {
        std::vector<int> ids;
        for (const auto& call : of(FfCall::Kind::erase)) {
            ids.push_back(call.id);
        }
        return ids;
    }
};

// Opens fake FF devices on `kernel`, as the evdev backend opens its event node: counts the
// openings, and fails with ENOENT while the device is unplugged.
drivers::FfDeviceOpener fake_ff_opener(const std::shared_ptr<FakeFfKernel>& kernel);

}  // namespace vibscore::testing
