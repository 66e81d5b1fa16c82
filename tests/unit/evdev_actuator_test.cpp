#include "daemon/drivers/evdev_actuator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/fakes/fake_ff_device.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using vibscore::testing::FakeFfKernel;
using vibscore::testing::FfCall;
using vibscore::testing::TempDir;
using vibscore::testing::WrittenEvent;

WrittenEvent play(int id) {
    return {EV_FF, static_cast<std::uint16_t>(id), 1};
}
WrittenEvent stop(int id) {
    return {EV_FF, static_cast<std::uint16_t>(id), 0};
}
WrittenEvent gain(std::int32_t value) {
    return {EV_FF, FF_GAIN, value};
}

struct Fixture : ::testing::Test {
    std::shared_ptr<FakeFfKernel> kernel = std::make_shared<FakeFfKernel>();
    EvdevSettings settings;

    std::unique_ptr<EvdevActuator> make() {
        return std::make_unique<EvdevActuator>(settings, fake_ff_opener(kernel));
    }
    void rumble_only() { kernel->features = {.rumble = true, .effect_slots = 16}; }
};

template <typename F>
std::string device_error_of(F&& f) {
    try {
        f();
    } catch (const DeviceError& error) {
        return error.what();
    }
    return "<no DeviceError>";
}

using EvdevActuatorTest = Fixture;

TEST_F(EvdevActuatorTest, PeriodicDeviceCapabilities) {
    auto actuator = make();
    EXPECT_EQ(actuator->driver_name(), "evdev");
    EXPECT_EQ(actuator->device_path(), "/dev/input/event5");
    const Capabilities capabilities = actuator->capabilities();
    EXPECT_TRUE(capabilities.amplitude_control);
    EXPECT_TRUE(capabilities.frequency_control);
    EXPECT_TRUE(capabilities.effect_memory);
    EXPECT_TRUE(capabilities.envelopes);
    EXPECT_TRUE(capabilities.gain_control);
    EXPECT_EQ(capabilities.max_on_time_s, 0.0);
}

TEST_F(EvdevActuatorTest, GainControlOnlyWithFfGain) {
    kernel->features.gain = false;
    EXPECT_FALSE(make()->capabilities().gain_control);
}

TEST_F(EvdevActuatorTest, SineEffectCarriesPeriodAndMagnitude) {
    auto actuator = make();
    actuator->apply({0.5, 200.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 1u);
    const ff_effect& effect = uploads[0].effect;
    EXPECT_EQ(effect.type, FF_PERIODIC);
    EXPECT_EQ(effect.id, -1);  // a new slot
    EXPECT_EQ(effect.u.periodic.waveform, FF_SINE);
    EXPECT_EQ(effect.u.periodic.period, 5);         // ms: 1000 / 200 Hz
    EXPECT_EQ(effect.u.periodic.magnitude, 16384);  // 0.5 * 0x7fff
    EXPECT_EQ(effect.u.periodic.offset, 0);
    EXPECT_EQ(effect.replay.length, 0);  // until stopped
    EXPECT_EQ(effect.replay.delay, 0);
    EXPECT_EQ(effect.u.periodic.envelope.attack_length, 0);
    EXPECT_EQ(effect.u.periodic.envelope.fade_length, 0);
    const auto writes = kernel->writes();
    ASSERT_EQ(writes.size(), 1u);
    EXPECT_THAT(writes[0].events, ElementsAre(play(uploads[0].id)));
}

TEST_F(EvdevActuatorTest, FullStrengthAndClamping) {
    auto actuator = make();
    actuator->apply({1.0, 100.0});
    actuator->apply({3.0, 100.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 2u);
    EXPECT_EQ(uploads[0].effect.u.periodic.magnitude, 0x7fff);
    EXPECT_EQ(uploads[0].effect.u.periodic.period, 10);
    EXPECT_EQ(uploads[1].effect.u.periodic.magnitude, 0x7fff);
}

TEST_F(EvdevActuatorTest, FrequencyZeroUsesTheDefaultFrequency) {
    auto actuator = make();
    actuator->apply({0.5, 0.0});
    settings.default_frequency_hz = 250.0;
    auto other = make();
    other->apply({0.5, 0.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 2u);
    EXPECT_EQ(uploads[0].effect.u.periodic.period, 6);  // 1000 / 175 = 5.7
    EXPECT_EQ(uploads[1].effect.u.periodic.period, 4);
}

TEST_F(EvdevActuatorTest, SquareWaveformWhenAskedFor) {
    settings.waveform = FfWaveform::square;
    make()->apply({0.5, 100.0});
    EXPECT_EQ(kernel->uploads().at(0).effect.u.periodic.waveform, FF_SQUARE);
}

TEST_F(EvdevActuatorTest, FallsBackToTheWaveformTheDeviceHas) {
    kernel->features.sine = false;
    make()->apply({0.5, 100.0});
    kernel->features.sine = true;
    kernel->features.square = false;
    settings.waveform = FfWaveform::square;
    make()->apply({0.5, 100.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 2u);
    EXPECT_EQ(uploads[0].effect.u.periodic.waveform, FF_SQUARE);
    EXPECT_EQ(uploads[1].effect.u.periodic.waveform, FF_SINE);
}

TEST_F(EvdevActuatorTest, RisingRampIsAnAttackFromTheStartLevel) {
    auto actuator = make();
    actuator->apply({0.2, 150.0, 0.8, 0.5});
    const ff_effect effect = kernel->uploads().at(0).effect;
    EXPECT_EQ(effect.u.periodic.magnitude, 26214);  // 0.8 * 0x7fff: where it ends and holds
    EXPECT_EQ(effect.u.periodic.envelope.attack_length, 500);
    EXPECT_EQ(effect.u.periodic.envelope.attack_level, 6553);  // 0.2 * 0x7fff, absolute
    EXPECT_EQ(effect.u.periodic.envelope.fade_length, 0);
    EXPECT_EQ(effect.u.periodic.period, 7);
    EXPECT_EQ(effect.replay.length, 0);
}

TEST_F(EvdevActuatorTest, FallingRampIsAnAttackFromAboveThatHolds) {
    auto actuator = make();
    actuator->apply({0.8, 100.0, 0.1, 0.25});
    const ff_effect effect = kernel->uploads().at(0).effect;
    EXPECT_EQ(effect.u.periodic.magnitude, 3277);  // 0.1 * 0x7fff
    EXPECT_EQ(effect.u.periodic.envelope.attack_length, 250);
    EXPECT_EQ(effect.u.periodic.envelope.attack_level, 26214);  // 0.8 * 0x7fff
    EXPECT_EQ(effect.u.periodic.envelope.fade_length, 0);
    EXPECT_EQ(effect.replay.length, 0);
}

TEST_F(EvdevActuatorTest, CrescendoFromSilencePlays) {
    auto actuator = make();
    actuator->apply({0.0, 100.0, 1.0, 2.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 1u);
    EXPECT_EQ(uploads[0].effect.u.periodic.magnitude, 0x7fff);
    EXPECT_EQ(uploads[0].effect.u.periodic.envelope.attack_level, 0);
    EXPECT_EQ(uploads[0].effect.u.periodic.envelope.attack_length, 2000);
    EXPECT_THAT(kernel->writes().at(0).events, ElementsAre(play(uploads[0].id)));
}

TEST_F(EvdevActuatorTest, ZeroAmplitudeStopsInsteadOfUploading) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    const int id = kernel->uploads().at(0).id;
    actuator->apply({0.0, 100.0});
    EXPECT_EQ(kernel->uploads().size(), 1u);
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(stop(id)));
}

TEST_F(EvdevActuatorTest, WithAntiPhaseANegativeDriveIsANegativeMagnitude) {
    EXPECT_FALSE(make()->capabilities().reverse);  // off unless the device is known to honour it
    settings.anti_phase = true;
    auto actuator = make();
    EXPECT_TRUE(actuator->capabilities().reverse);
    actuator->apply({-1.0, 175.0});
    actuator->apply({-0.5, 175.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 2u);
    EXPECT_EQ(uploads[0].effect.u.periodic.magnitude, -0x7fff);
    EXPECT_EQ(uploads[1].effect.u.periodic.magnitude, -16384);
    EXPECT_THAT(kernel->writes().back().events.back(), play(uploads[1].id));
}

TEST_F(EvdevActuatorTest, WithoutAntiPhaseANegativeDrivePlaysNothing) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    const int id = kernel->uploads().at(0).id;
    actuator->apply({-0.5, 100.0});
    EXPECT_EQ(kernel->uploads().size(), 1u);
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(stop(id)));
}

TEST_F(EvdevActuatorTest, RumbleDevicesHaveNoAntiPhase) {
    rumble_only();
    settings.anti_phase = true;
    EXPECT_FALSE(make()->capabilities().reverse);
}

TEST_F(EvdevActuatorTest, RumbleOnlyDevice) {
    rumble_only();
    auto actuator = make();
    const Capabilities capabilities = actuator->capabilities();
    EXPECT_TRUE(capabilities.amplitude_control);
    EXPECT_TRUE(capabilities.effect_memory);
    EXPECT_FALSE(capabilities.frequency_control);
    EXPECT_FALSE(capabilities.envelopes);
    EXPECT_FALSE(capabilities.gain_control);

    actuator->apply({0.5, 200.0});
    const ff_effect effect = kernel->uploads().at(0).effect;
    EXPECT_EQ(effect.type, FF_RUMBLE);
    EXPECT_EQ(effect.u.rumble.strong_magnitude, 32768);  // 0.5 * 0xffff
    EXPECT_EQ(effect.u.rumble.weak_magnitude, 0);
    EXPECT_EQ(effect.replay.length, 0);
}

TEST_F(EvdevActuatorTest, FrequencyControlCanBeDeniedForMemorylessVibras) {
    settings.frequency_control = false;
    const Capabilities capabilities = make()->capabilities();
    EXPECT_FALSE(capabilities.frequency_control);
    EXPECT_TRUE(capabilities.envelopes);  // still periodic effects with envelopes
}

TEST_F(EvdevActuatorTest, RumbleMotorSetting) {
    rumble_only();
    settings.rumble_motor = RumbleMotor::weak;
    make()->apply({1.0, 0.0});
    settings.rumble_motor = RumbleMotor::both;
    make()->apply({0.25, 0.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 2u);
    EXPECT_EQ(uploads[0].effect.u.rumble.strong_magnitude, 0);
    EXPECT_EQ(uploads[0].effect.u.rumble.weak_magnitude, 0xffff);
    EXPECT_EQ(uploads[1].effect.u.rumble.strong_magnitude, 16384);
    EXPECT_EQ(uploads[1].effect.u.rumble.weak_magnitude, 16384);
}

TEST_F(EvdevActuatorTest, RumbleGainWithFfGain) {
    kernel->features = {.rumble = true, .gain = true, .effect_slots = 16};
    EXPECT_TRUE(make()->capabilities().gain_control);
}

TEST_F(EvdevActuatorTest, PeriodicPreferredWhenTheDeviceHasBoth) {
    kernel->features.rumble = true;
    make()->apply({0.5, 100.0});
    EXPECT_EQ(kernel->uploads().at(0).effect.type, FF_PERIODIC);
}

TEST_F(EvdevActuatorTest, SetGainWritesFfGain) {
    auto actuator = make();
    actuator->set_gain(0.5);
    actuator->set_gain(1.0);
    actuator->set_gain(0.0);
    const auto writes = kernel->writes();
    ASSERT_EQ(writes.size(), 3u);
    EXPECT_THAT(writes[0].events, ElementsAre(gain(32768)));
    EXPECT_THAT(writes[1].events, ElementsAre(gain(0xffff)));
    EXPECT_THAT(writes[2].events, ElementsAre(gain(0)));
}

TEST_F(EvdevActuatorTest, SetGainWithoutFfGainWritesNothing) {
    kernel->features.gain = false;
    auto actuator = make();
    actuator->set_gain(0.5);
    EXPECT_THAT(kernel->calls, IsEmpty());
}

TEST_F(EvdevActuatorTest, PreparedDriveStartsWithOneWriteThatStopsTheOld) {
    auto actuator = make();
    const Drive first{0.5, 100.0};
    const Drive second{0.7, 200.0};
    const Drive third{0.3, 50.0};
    actuator->apply(first);
    const int a = kernel->uploads().at(0).id;

    actuator->prepare(second);
    ASSERT_EQ(kernel->uploads().size(), 2u);
    const int b = kernel->uploads().at(1).id;
    EXPECT_NE(a, b);
    EXPECT_EQ(kernel->uploads().at(1).effect.u.periodic.period, 5);

    const std::size_t calls_before = kernel->calls.size();
    actuator->apply(second);
    ASSERT_EQ(kernel->calls.size(), calls_before + 1);  // nothing but one write
    EXPECT_THAT(kernel->calls.back().events, ElementsAre(stop(a), play(b)));

    // The slots have swapped: the next drive goes into the first slot, updated in place.
    actuator->prepare(third);
    ASSERT_EQ(kernel->uploads().size(), 3u);
    EXPECT_EQ(kernel->uploads().at(2).effect.id, a);
    actuator->apply(third);
    EXPECT_THAT(kernel->calls.back().events, ElementsAre(stop(b), play(a)));
    EXPECT_EQ(kernel->uploads().size(), 3u);
    EXPECT_EQ(kernel->live.size(), 2u);  // never more than the two slots
}

TEST_F(EvdevActuatorTest, UnpreparedDriveIsUploadedIntoTheSpareThenOneWrite) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    const int a = kernel->uploads().at(0).id;
    actuator->apply({0.6, 100.0});
    ASSERT_EQ(kernel->uploads().size(), 2u);
    const int b = kernel->uploads().at(1).id;
    EXPECT_NE(a, b);
    const auto writes = kernel->writes();
    ASSERT_EQ(writes.size(), 2u);
    EXPECT_THAT(writes[1].events, ElementsAre(stop(a), play(b)));
}

TEST_F(EvdevActuatorTest, DriveOtherThanThePreparedOneReplacesIt) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    const int a = kernel->uploads().at(0).id;
    actuator->prepare({0.6, 100.0});
    const int b = kernel->uploads().at(1).id;
    actuator->apply({0.9, 100.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 3u);
    EXPECT_EQ(uploads[2].effect.id, b);  // the spare slot again, updated in place
    EXPECT_EQ(uploads[2].effect.u.periodic.magnitude, 29490);
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(stop(a), play(b)));
}

TEST_F(EvdevActuatorTest, PrepareTwiceWithTheSameDriveUploadsOnce) {
    auto actuator = make();
    actuator->prepare({0.5, 100.0});
    actuator->prepare({0.5, 100.0});
    EXPECT_EQ(kernel->uploads().size(), 1u);
    actuator->apply({0.5, 100.0});
    EXPECT_EQ(kernel->uploads().size(), 1u);
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(play(kernel->uploads()[0].id)));
}

TEST_F(EvdevActuatorTest, OffStopsThePlayingEffectAndKeepsThePreparedOne) {
    auto actuator = make();
    actuator->off();  // nothing plays: nothing to write
    EXPECT_THAT(kernel->calls, IsEmpty());
    actuator->apply({0.5, 100.0});
    const int a = kernel->uploads().at(0).id;
    actuator->prepare({0.6, 100.0});
    const int b = kernel->uploads().at(1).id;
    actuator->off();
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(stop(a)));
    actuator->off();
    EXPECT_EQ(kernel->writes().size(), 2u);
    actuator->apply({0.6, 100.0});
    EXPECT_EQ(kernel->uploads().size(), 2u);
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(play(b)));
}

TEST_F(EvdevActuatorTest, DestructionStopsAndErasesEveryEffect) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    actuator->apply({0.6, 100.0});
    actuator->prepare({0.7, 100.0});
    const int a = kernel->uploads().at(0).id;
    const int b = kernel->uploads().at(1).id;
    actuator.reset();
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(stop(b)));
    EXPECT_THAT(kernel->erased(), ::testing::UnorderedElementsAre(a, b));
    EXPECT_TRUE(kernel->live.empty());
}

TEST_F(EvdevActuatorTest, DestructionWithNothingUploadedTouchesNothing) {
    make().reset();
    EXPECT_THAT(kernel->calls, IsEmpty());
}

TEST_F(EvdevActuatorTest, SingleSlotDeviceUpdatesItsOneEffectInPlace) {
    kernel->features.effect_slots = 1;
    auto actuator = make();
    EXPECT_FALSE(actuator->capabilities().effect_memory);
    actuator->apply({0.5, 100.0});
    actuator->prepare({0.6, 100.0});  // nowhere to put it ahead
    EXPECT_EQ(kernel->uploads().size(), 1u);
    actuator->apply({0.6, 100.0});
    const auto uploads = kernel->uploads();
    ASSERT_EQ(uploads.size(), 2u);
    EXPECT_EQ(uploads[1].effect.id, uploads[0].id);
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(play(uploads[0].id)));
}

TEST_F(EvdevActuatorTest, RemovalThrowsNamingTheDeviceAndReopensOnTheNextDrive) {
    auto actuator = make();
    actuator->set_gain(0.25);
    actuator->apply({0.5, 100.0});
    ASSERT_EQ(kernel->opens, 1);

    // The held node fails; the device is looked for again at once, and is not there.
    kernel->unplug();
    EXPECT_EQ(device_error_of([&] {
                  actuator->apply({0.6, 100.0});
              }),
              "evdev /dev/input/event5: No such file or directory (open)");
    EXPECT_EQ(kernel->opens, 2);
    EXPECT_EQ(actuator->device_path(), "");
    actuator->off();  // nothing left to stop, and no exception

    // Still away: the next drive tries to open it again and says why that failed.
    EXPECT_THAT(device_error_of([&] {
                    actuator->apply({0.6, 100.0});
                }),
                HasSubstr("evdev /dev/input/event5: No such file or directory"));
    EXPECT_EQ(kernel->opens, 3);

    kernel->present = true;
    const std::size_t calls_before = kernel->calls.size();
    actuator->apply({0.6, 100.0});
    EXPECT_EQ(kernel->opens, 4);
    EXPECT_EQ(actuator->device_path(), "/dev/input/event5");
    const std::vector<FfCall> after(kernel->calls.begin() + calls_before, kernel->calls.end());
    ASSERT_EQ(after.size(), 3u);
    EXPECT_THAT(after[0].events, ElementsAre(gain(16384)));  // the gain set before it went
    EXPECT_EQ(after[1].kind, FfCall::Kind::upload);
    EXPECT_EQ(after[1].effect.id, -1);                             // fresh slots on the new opening
    EXPECT_THAT(after[2].events, ElementsAre(play(after[1].id)));  // nothing to stop there
    EXPECT_EQ(after[2].generation, 2u);
}

TEST_F(EvdevActuatorTest, ADeviceReplugedSinceTheLastCallIsOpenedAgainAndTheDriveGoesThrough) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    actuator->off();
    kernel->unplug();  // and back, while nothing played: the held node is dead
    kernel->present = true;

    actuator->set_gain(0.5);  // finds the node gone: no error, the next drive sends it
    EXPECT_EQ(actuator->device_path(), "");
    actuator->apply({0.6, 100.0});
    EXPECT_EQ(kernel->opens, 2);
    EXPECT_EQ(actuator->device_path(), "/dev/input/event5");
    const auto writes = kernel->writes();
    ASSERT_GE(writes.size(), 2u);
    EXPECT_THAT(writes[writes.size() - 2].events, ElementsAre(gain(32768)));
    EXPECT_EQ(kernel->uploads().back().generation, 2u);
    EXPECT_THAT(writes.back().events, ElementsAre(play(kernel->uploads().back().id)));

    // The same for a drive prepared ahead.
    kernel->unplug();
    kernel->present = true;
    actuator->prepare({0.7, 100.0});
    EXPECT_EQ(kernel->opens, 3);
    EXPECT_EQ(kernel->uploads().back().generation, 3u);
}

TEST_F(EvdevActuatorTest, RemovalNoticedByOffIsSwallowedAndReopenedByPrepare) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    kernel->unplug();
    actuator->off();
    EXPECT_EQ(actuator->device_path(), "");
    kernel->present = true;
    actuator->prepare({0.6, 100.0});
    EXPECT_EQ(kernel->opens, 2);
    EXPECT_EQ(kernel->uploads().back().generation, 2u);
}

TEST_F(EvdevActuatorTest, WriteFailureOfAGoneDeviceClosesItAndTriesAFreshOpening) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    actuator->prepare({0.6, 100.0});
    kernel->fail_next_errno = EIO;
    actuator->apply({0.6, 100.0});  // the write fails; the node is opened again, and it works
    EXPECT_EQ(kernel->opens, 2);
    EXPECT_EQ(kernel->uploads().back().effect.id, -1);  // into the fresh opening's own slot
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(play(kernel->uploads().back().id)));
    EXPECT_EQ(actuator->device_path(), "/dev/input/event5");
}

TEST_F(EvdevActuatorTest, OtherErrorsKeepTheDeviceOpen) {
    auto actuator = make();
    kernel->fail_next_errno = EINVAL;
    EXPECT_EQ(device_error_of([&] {
                  actuator->apply({0.5, 100.0});
              }),
              "evdev /dev/input/event5: Invalid argument (EVIOCSFF)");
    EXPECT_EQ(actuator->device_path(), "/dev/input/event5");
    actuator->apply({0.5, 100.0});
    EXPECT_EQ(kernel->opens, 1);
    EXPECT_EQ(kernel->uploads().size(), 1u);
}

TEST_F(EvdevActuatorTest, FailedStopIsRetriedByTheNextDrive) {
    auto actuator = make();
    actuator->apply({0.5, 100.0});
    const int a = kernel->uploads().at(0).id;
    kernel->fail_next_errno = EINVAL;
    actuator->off();  // swallowed
    actuator->apply({0.6, 100.0});
    const int b = kernel->uploads().at(1).id;
    EXPECT_THAT(kernel->writes().back().events, ElementsAre(stop(a), play(b)));
}

TEST_F(EvdevActuatorTest, DeviceWithoutPlayableEffectsIsRefusedNamingIt) {
    kernel->features = {.periodic = true, .gain = true, .effect_slots = 16};  // no waveform
    EXPECT_THAT(device_error_of([&] { make(); }),
                HasSubstr("evdev /dev/input/event5 (fake vibrator): no force-feedback effect"));
    kernel->features = {.rumble = true, .effect_slots = 0};
    EXPECT_THAT(device_error_of([&] { make(); }), HasSubstr("/dev/input/event5"));
}

TEST_F(EvdevActuatorTest, MissingDeviceFailsAtConstruction) {
    kernel->present = false;
    EXPECT_THAT(device_error_of([&] { make(); }),
                HasSubstr("evdev /dev/input/event5: No such file or directory (open)"));
}

TEST(FfDeviceError, GoneMeansEnodevEnoentOrEio) {
    EXPECT_TRUE(FfDeviceError("p", "write", ENODEV).device_gone());
    EXPECT_TRUE(FfDeviceError("p", "write", ENOENT).device_gone());
    EXPECT_TRUE(FfDeviceError("p", "write", EIO).device_gone());
    EXPECT_FALSE(FfDeviceError("p", "write", EINVAL).device_gone());
    EXPECT_EQ(FfDeviceError("p", "write", ENODEV).error_number(), ENODEV);
    EXPECT_STREQ(FfDeviceError("/dev/input/event5", "write", ENODEV).what(),
                 "evdev /dev/input/event5: No such device (write)");
}

TEST(OpenFfDevice, MissingNodeNamesItsPath) {
    TempDir dir;
    const std::string path = (dir.path() / "event9").string();
    try {
        open_ff_device(path);
        FAIL() << "no exception";
    } catch (const FfDeviceError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "evdev " + path + ": No such file or directory (open)");
        EXPECT_TRUE(error.device_gone());
    }
}

TEST(OpenFfDevice, NodeThatIsNotAnEventDeviceIsRefused) {
    EXPECT_THAT(device_error_of([] { open_ff_device("/dev/null"); }),
                HasSubstr("evdev /dev/null: Inappropriate ioctl for device"));
}

TEST(MakeEvdevActuator, ConfiguredDeviceThatIsMissingFailsNamingIt) {
    TempDir dir;
    const std::string path = (dir.path() / "event3").string();
    EXPECT_THAT(device_error_of([&] {
                    make_evdev_actuator({{"device", path}});
                }),
                HasSubstr("evdev " + path + ": No such file or directory"));
}

TEST(MakeEvdevActuator, DiscoveryThatFindsNothingSaysWhereItLooked) {
    TempDir dir;
    dir.write("event0", "");  // a plain file: no event device
    const std::string message = device_error_of([&] {
        make_evdev_actuator(
            {{"input-dir", dir.path().string()}, {"udev-data", (dir.path() / "udev").string()}});
    });
    EXPECT_THAT(message, HasSubstr("no force-feedback device in " + dir.path().string()));
    EXPECT_THAT(message, HasSubstr("1 event device, none with force feedback"));
}

TEST(MakeEvdevActuator, BadSettingsAreRejectedNamingKeyAndValue) {
    const auto message_of = [](const std::map<std::string, std::string>& settings) {
        try {
            make_evdev_actuator(settings);
        } catch (const std::invalid_argument& error) {
            return std::string(error.what());
        }
        return std::string("<no invalid_argument>");
    };
    EXPECT_THAT(message_of({{"waveform", "triangle"}}),
                HasSubstr("evdev setting waveform = \"triangle\""));
    EXPECT_THAT(message_of({{"default-frequency-hz", "0"}}),
                HasSubstr("evdev setting default-frequency-hz = \"0\""));
    EXPECT_THAT(message_of({{"rumble-motor", "left"}}),
                HasSubstr("evdev setting rumble-motor = \"left\""));
    EXPECT_THAT(message_of({{"colour", "red"}}), HasSubstr("unknown evdev setting colour"));
    EXPECT_THAT(message_of({{"device", ""}}), HasSubstr("evdev setting device = \"\""));
}

}  // namespace
}  // namespace vibscore::drivers
