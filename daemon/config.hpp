#pragma once

#include "actuator/declaration.hpp"
#include "config.h"
#include "daemon/admission.hpp"
#include "daemon/device_clefs.hpp"
#include "daemon/playback_limits.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vibscore::drivers {
class ModuleCatalog;
}

namespace vibscore::daemon {

// vibscored.conf: INI sections of "key = value" lines, read by common/ini_reader.hpp (the client's
// --actuator FILE too). '#' and ';' start a comment at the start of a line or after a blank;
// anywhere else they are an error, as is a key set twice in a section.
//   [daemon]  driver, drivers-dir, store, shipped, separation-ms, requests-per-second,
//             request-burst, rt-priority
//   [actuator] the actuator's physics, declared once (actuator/declaration.hpp)
//   [limits]  max-on-time, max-on-time-USAGE, cool-down (daemon/playback_limits.hpp)
//             document-bytes-per-second, document-burst-bytes, work-cpu-per-second,
//             work-cpu-burst, connection-share (daemon/admission.hpp)
//   [clefs]   WRITTEN = DEVICE: the clef bars written for WRITTEN play through on this device;
//             "* = DEVICE" for any other clef; "fit = auto" fits every other clef to [actuator]
//   [NAME]    the settings of driver NAME (e.g. [sim] model = erm), handed to that driver
// docs/daemon.md documents every key.
struct DaemonConfig {
    std::string driver = "sim";
    std::filesystem::path store = "/var/lib/vibscore";
    std::filesystem::path shipped;  // default: shipped_clefs_folder() (json/build_tree.hpp)
    std::filesystem::path drivers_dir = VIBSCORE_DRIVERDIR;  // driver modules (*.so)
    double separation_ms = 30.0;
    double requests_per_second = 50.0;
    double request_burst = 100.0;
    int rt_priority = 40;  // SCHED_FIFO of the playback thread; 0: normal scheduling
    std::map<std::string, std::map<std::string, std::string>> driver_settings;  // by driver
    DeviceClefs device_clefs;
    std::optional<actuator::Declaration> actuator;  // [actuator]; nothing: playback as written
    PlaybackLimits limits;                          // [limits]
    // [limits]' admission budgets; their request rate and burst are [daemon]'s.
    AdmissionBudgets admission;
    // Where actuator's numbers come from: "declared", or "measured <ISO date>" when the store
    // holds a calibration of the declared kind (calibration_state.hpp); "" when none is declared.
    std::string actuator_source;
    // Where each [section] begins and each of its keys is set, as "file:line", for messages:
    // section_lines for every section but [daemon], setting_lines for every key ([daemon]'s and
    // [clefs]' too).
    std::map<std::string, std::string> section_lines;
    std::map<std::string, std::map<std::string, std::string>> setting_lines;

    // Not from the file: what read_config() found and decided when it read it.
    // The driver modules of drivers_dir, each tried once (none: only the built-in drivers).
    std::shared_ptr<const drivers::ModuleCatalog> modules;
    // The store's file that names the driver module in use (module_record.hpp); empty for
    // --safe-off, which must leave it for the next start to find.
    std::filesystem::path module_record;

    const std::map<std::string, std::string>& settings_of(const std::string& driver) const;
    // "file:line: " of a driver's setting (or of its section when the key is not set there);
    // empty when the settings did not come from a file.
    std::string where(const std::string& driver, const std::string& key) const;
};

// The file is wrong; the message is "path:line: what", naming the key and value.
class ConfigError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

DaemonConfig parse_config(const std::string& text, const std::string& file,
                          DaemonConfig defaults = {});
// Throws ConfigError naming the path and the reason when the file cannot be read.
DaemonConfig load_config(const std::filesystem::path& path, DaemonConfig defaults = {});

// A warning for each [clefs] line whose device clef the registry does not hold (yet: it may be
// composed later), naming its file:line, key and value; Play would refuse the scores it maps.
std::vector<std::string> missing_device_clefs(const DaemonConfig& config, const Registry& registry);

// Sections besides [daemon] and the backends' that configure parts of the service.
inline constexpr const char* kActuatorSection = actuator::kSection;
inline constexpr const char* kLimitsSection = "limits";
inline constexpr const char* kCalibrationSection = "calibration";  // accelerometer = auto|PATH
inline constexpr const char* kServiceSections[] = {"clefs", "virtual-vibra", kActuatorSection,
                                                   kLimitsSection, kCalibrationSection};

// A warning for each section of `config` that is neither [daemon], a service section nor one of
// `known` (the drivers), whose keys therefore apply nowhere: "file:line: unknown section [x] ...
// (did you mean [y]?)".
std::vector<std::string> unknown_sections(const DaemonConfig& config,
                                          const std::vector<std::string>& known);

}  // namespace vibscore::daemon
