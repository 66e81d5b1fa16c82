#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/ini_reader.hpp"

// The actuator's physics, declared once: what [actuator] in vibscored.conf says, read the same
// way by the daemon (config, sim, compensation) and the client (render --actuator, check).
namespace vibscore::actuator {

enum class Kind { erm, lra };
enum class Brake { none, reverse };

// Times in seconds, frequencies in hertz; docs/drivers.md ("Declaring the actuator") says how to
// read each one from a datasheet.
struct Declaration {
    Kind kind = Kind::erm;
    // The drive (0..1 of the backend's full scale) the actuator is rated for: a clef's strength 1.
    double rated_drive = 1.0;
    double spin_up_s = 0.040;     // ERM: time constant of its speed while driven
    double spin_down_s = 0.080;   // ERM: time constant while coasting
    double resonance_hz = 175.0;  // LRA: resonance f0
    double q = 15.0;              // LRA: quality factor; envelope time constant q / (pi f0)
    // LRA: how far the actual part may be from resonance_hz and q, as fractions (0.05 = 5 %):
    // compensation plans for every actuator within them, not only the declared one
    // (render::Uncertainty). The defaults are the part-to-part spread of a datasheet's numbers
    // (issue 32); a measured resonance and Q are known far better. 0 takes the numbers as exact.
    double resonance_tolerance = 0.05;
    double q_tolerance = 0.40;
    Brake brake = Brake::none;  // reverse: the board can drive backwards, so it can brake
    bool compensation = true;

    bool operator==(const Declaration&) const = default;
};

// The limits of each number, as the keys give them (milliseconds for times). Messages and docs
// are built from these, so a limit is written once.
struct Limit {
    const char* key;
    double min, max;
    bool min_allowed;  // false: min itself is refused (a drive or a time of 0 is meaningless)
};
inline constexpr Limit kRatedDrive{"rated-drive", 0.0, 1.0, false};
inline constexpr Limit kSpinUpMs{"spin-up-ms", 1.0, 5000.0, true};
inline constexpr Limit kSpinDownMs{"spin-down-ms", 1.0, 10000.0, true};
inline constexpr Limit kResonanceHz{"resonance-hz", 10.0, 1000.0, true};
// Below Q 1 a resonator hardly rings, and its envelope is no longer one exponential.
inline constexpr Limit kQ{"q", 1.0, 500.0, true};
// Percent. Past half the resonance the neighbours are other actuators; past 90 % of Q, one that
// hardly rings (and the planner's members need Q above 0).
inline constexpr Limit kResonanceTolerancePercent{"resonance-tolerance-percent", 0.0, 50.0, true};
inline constexpr Limit kQTolerancePercent{"q-tolerance-percent", 0.0, 90.0, true};

// The keys of [actuator], in the order the docs list them.
inline constexpr const char* kKeys[] = {"kind",
                                        "rated-drive",
                                        "spin-up-ms",
                                        "spin-down-ms",
                                        "resonance-hz",
                                        "q",
                                        "resonance-tolerance-percent",
                                        "q-tolerance-percent",
                                        "brake",
                                        "compensation"};

// One "key = value" line of the section and where it was written ("file:line"; may be empty).
struct Setting {
    std::string key;
    std::string value;
    std::string where;
};

// A bad section; the message starts with "file:line: " when the line is known and names the key
// and the value.
class DeclarationError : public std::invalid_argument {
  public:
    DeclarationError(std::string key, const std::string& message)
        : std::invalid_argument(message), key_(std::move(key)) {}
    const std::string& key() const { return key_; }

  private:
    std::string key_;
};

// Reads the section's lines (`section_where` is where its header is, for what is missing).
// `kind` is required; every other key has the default above. Keys of the other kind (spin-up-ms
// for an LRA), unknown keys, a key set twice and values out of range are DeclarationErrors.
Declaration parse_declaration(const std::vector<Setting>& settings,
                              const std::string& section_where);

// The section's name in an INI file: "[actuator]".
inline constexpr const char* kSection = "actuator";

// The [actuator] section of an INI text (vibscored.conf, or a file of its own): its lines, and
// where its header is (the first, when the file opens it twice); nothing when the text has none.
// The text is read by common/ini_reader.hpp, the daemon's reader, so the client and the daemon
// read one file the same way: a line the reader refuses anywhere in the file (a malformed header,
// "kind = lra#x") is a DeclarationError naming file, line and value.
struct Section {
    std::vector<Setting> settings;
    std::string where;
};
std::optional<Section> find_section(const std::vector<IniLine>& lines);
std::optional<Section> find_section(const std::string& text, const std::string& file);

// find_section, then parse_declaration: the declaration a file makes, if any.
std::optional<Declaration> read_declaration(const std::string& text, const std::string& file);

// One line for logs and `vibscore info`: "lra 175 Hz q 15, rated-drive 0.7, brake reverse,
// compensation on".
std::string describe(const Declaration& declaration);

// The declaration as the keys of [actuator] would write it (for D-Bus and round trips); the
// tolerances only where they differ from their defaults.
std::vector<std::pair<std::string, std::string>> to_settings(const Declaration& declaration);

// The reverse of to_settings: the declaration the daemon's Haptics1.Actuator property publishes,
// read by the one function the client's verbs and the editor share. Throws DeclarationError,
// naming `source` (e.g. "vibscored's Actuator property") for the key and value at fault.
Declaration from_settings(const std::map<std::string, std::string>& settings,
                          const std::string& source);

// The envelope time constant of an LRA: the time its ringing takes to decay by 1/e.
double lra_time_constant_s(double resonance_hz, double q);

}  // namespace vibscore::actuator
