#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/ff_device.hpp"

namespace vibscore::drivers {

enum class FfWaveform { sine, square };
enum class RumbleMotor { strong, weak, both };

struct EvdevSettings {
    FfWaveform waveform = FfWaveform::sine;  // preferred; the device may only have the other
    double default_frequency_hz = 175.0;     // for drives with frequency 0
    RumbleMotor rumble_motor = RumbleMotor::strong;
    // ff-memless drivers (most phone vibras) claim FF_PERIODIC but ignore the period: false
    // stops the player from sending frequencies such a device cannot play.
    bool frequency_control = true;
    // The device plays a periodic effect of negative magnitude as the same waveform inverted
    // (anti-phase), so the renderer may brake with it. Not ff-memless drivers, which play
    // |magnitude| as a rumble: braking would become full strength. Off unless a test on the
    // device shows it (docs/drivers/evdev.md).
    bool anti_phase = false;
};

// Opens the device to drive: the configured node, or whatever discovery finds now. Called again
// after the device went away. Throws DeviceError when there is none.
using FfDeviceOpener = std::function<std::unique_ptr<FfDevice>()>;

// An actuator behind the kernel's force-feedback interface (a phone's vibra, a gamepad's rumble
// motors, a uinput device). Devices with periodic effects play each drive as an endless sine or
// square effect with its frequency and, for ramps, an attack envelope; rumble-only devices get a
// rumble effect whose strength the player updates along ramps.
//
// Two effect slots are kept: the playing one and a spare. prepare(next) uploads the next drive
// into the spare ahead of its onset, so apply(next) is a single write() that stops the playing
// effect and starts the spare one; the slots then swap roles. Every effect uploaded is erased
// again, at the latest in the destructor.
//
// When the device goes away (ENODEV, ENOENT, EIO) the device is closed. A call that finds the
// device it held gone opens it again through the opener and tries once more (the device may
// be back already, replugged while the daemon was idle); if that fails too, it throws
// DeviceError, and the next apply() or prepare() tries again.
class EvdevActuator : public Actuator {
  public:
    // Opens the device at once. Throws DeviceError when it cannot be opened or has no effect
    // this backend can play (FF_RUMBLE, or FF_PERIODIC with FF_SINE or FF_SQUARE).
    EvdevActuator(EvdevSettings settings, FfDeviceOpener opener);
    ~EvdevActuator() override;
    EvdevActuator(const EvdevActuator&) = delete;
    EvdevActuator& operator=(const EvdevActuator&) = delete;

    std::string_view driver_name() const override { return "evdev"; }
    // Those of the device opened last.
    Capabilities capabilities() const override;

    // Throws DeviceError naming the device when a kernel call fails or the device cannot be
    // opened again.
    void apply(const Drive& drive) override;
    void off() noexcept override;
    void prepare(const Drive& next) override;
    // Remembered and sent again whenever the device is opened again. Throws DeviceError when the
    // write fails for another reason than the device having gone.
    void set_gain(double gain) override;

    // The node in use, empty while the device is closed after it went away.
    std::string device_path() const;

  private:
    enum class EffectKind { periodic, rumble };

    struct Slot {
        int id = -1;                 // kernel effect id; -1 until the first upload
        std::uint16_t waveform = 0;  // of the effect uploaded, for periodic ones
        std::optional<Drive> loaded;
    };

    void ensure_open();
    void close_device() noexcept;
    // Runs a kernel call; a device that has gone is closed before the error goes on.
    template <typename Call>
    void guarded(Call&& call);
    // Runs one of the player's calls; once more on a fresh opening if the device held open
    // when it began turns out to have gone.
    template <typename Operation>
    void reopening_once(Operation&& operation);

    void apply_now(const Drive& drive);
    void prepare_now(const Drive& next);
    bool plays_nothing(const Drive& drive) const;
    // The drive's strength for this device: -1..1 where it plays anti-phase, else 0..1.
    double level(double amplitude) const;
    ff_effect effect_for(const Drive& drive) const;
    void load(Slot& slot, const Drive& drive);
    void stop_playing();

    EvdevSettings settings_;
    FfDeviceOpener opener_;
    std::unique_ptr<FfDevice> device_;
    EffectKind kind_ = EffectKind::periodic;
    std::uint16_t waveform_ = FF_SINE;
    Capabilities capabilities_;
    bool has_gain_ = false;
    std::size_t slot_count_ = 2;  // 1 on a device that holds a single effect
    std::array<Slot, 2> slots_;
    std::optional<std::size_t> playing_;
    std::size_t spare_ = 0;
    std::optional<double> gain_;
};

// Builds an EvdevActuator from the [evdev] settings of the daemon's configuration:
//   device                the event node (e.g. /dev/input/event3); default: discovery
//   input-dir             where discovery looks for event nodes (default /dev/input)
//   udev-data             udev's database, for E:FEEDBACKD_TYPE=vibra (default /run/udev/data)
//   waveform              sine | square (default sine) for periodic devices
//   default-frequency-hz  frequency for drives without one (default 175)
//   rumble-motor          strong | weak | both (default strong) for rumble-only devices
//   anti-phase            true | false (default false): negative magnitudes brake (periodic)
// Throws std::invalid_argument naming a bad or unknown setting, DeviceError when no device can
// be opened (saying where it looked).
std::unique_ptr<Actuator> make_evdev_actuator(const std::map<std::string, std::string>& settings);

}  // namespace vibscore::drivers
