#pragma once

#include <map>
#include <string>
#include <vector>

namespace vibscore::daemon {

// What org.vibscore.Haptics1's properties that live on the playback thread say (the running
// backend, the declared actuator, the master intensity), as one immutable copy the playback
// thread publishes whenever one of them changes (PlaybackThread::publish). The bus thread reads
// them from it, so a property read never waits for the playback thread: a driver stuck in the
// kernel holds playback, not Get.
struct BusProperties {
    std::string driver;
    std::string driver_reason;
    std::vector<std::string> capabilities;
    std::map<std::string, std::string> actuator;  // the declaration's settings; empty: none
    double intensity = 1.0;                       // the player's master intensity
};

}  // namespace vibscore::daemon
