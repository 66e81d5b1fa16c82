// Compensation (daemon/render/drive_planner.*, the ActuatorDrives stage of cue_adaptation): each
// rule against the actuator model's closed forms, and each limit at its edge.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <span>

#include "actuator/physics.hpp"
#include "bench/feel_plant.hpp"
#include "bench/note_phrases.hpp"
#include "daemon/render/actuator_response.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/drive_planner.hpp"
#include "daemon/render/performance.hpp"
#include "tests/support/example_actuators.hpp"
#include "tests/support/support.hpp"

namespace vibscore::render {
namespace {

using vibscore::testing::example_erm;
using vibscore::testing::example_lra;

using actuator::Brake;
using actuator::Declaration;
using actuator::Kind;
using actuator::Physics;
using actuator::State;

constexpr double kRated = 0.7;
constexpr double kFull = 1.0 / kRated;  // strength at full scale
constexpr double kUp = 0.040, kDown = 0.080;

const double kTau = actuator::lra_time_constant_s(175.0, 15.0);

std::vector<Cue> plan(DrivePlanner& planner, double at, double until, double strength,
                      double frequency = 0.0, bool silence_follows = false) {
    std::vector<Cue> out;
    planner.segment(at, until, strength, frequency, silence_follows, out);
    return out;
}

MATCHER_P3(DriveIs, at, amplitude, tolerance, "") {
    return std::abs(arg.at - at) <= tolerance && std::abs(arg.amplitude - amplitude) <= 1e-12;
}

// The strength the actuator reaches at `t` under `drives`.
double strength_at(const Declaration& d, const std::vector<Cue>& drives, double t) {
    const auto samples = produced_strength(d, drives, 1e6, static_cast<std::size_t>(t * 1e6) + 1);
    return samples.back();
}

TEST(DrivePlanner, StrengthOneIsTheRatedDrive) {
    DrivePlanner planner(example_erm(), {.compensation = false});
    EXPECT_THAT(plan(planner, 0.0, 1.0, 1.0), ::testing::ElementsAre(DriveIs(0.0, kRated, 0.0)));
    EXPECT_THAT(plan(planner, 1.0, 2.0, 0.5), ::testing::ElementsAre(DriveIs(1.0, 0.35, 0.0)));
    // Compensation off still never exceeds full scale.
    EXPECT_THAT(plan(planner, 2.0, 3.0, 2.0), ::testing::ElementsAre(DriveIs(2.0, 1.0, 0.0)));
}

TEST(DrivePlanner, AnOnsetIsOverdrivenExactlyAsLongAsTheModelTakesThenHeld) {
    DrivePlanner planner(example_erm(), {});
    const auto drives = plan(planner, 0.0, 1.0, 1.0);
    const double overdrive = kUp * std::log(kFull / (kFull - 1.0));
    ASSERT_THAT(drives,
                ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0), DriveIs(overdrive, kRated, 1e-12)));
    EXPECT_NEAR(strength_at(example_erm(), drives, overdrive), 1.0, 1e-5);
    EXPECT_NEAR(Physics::strength(planner.carry().state), 1.0, 1e-9);
}

TEST(DrivePlanner, OverdriveStartsFromWhereTheActuatorIsMidDecay) {
    DrivePlanner planner(example_erm(Brake::none), {});
    plan(planner, 0.0, 1.0, 1.0);
    plan(planner, 1.0, 1.02, 0.0);  // coasts 20 ms: down to e^(-1/4)
    const double left = std::exp(-0.020 / kDown);
    const auto drives = plan(planner, 1.02, 2.0, 1.0);
    const double overdrive = kUp * std::log((kFull - left) / (kFull - 1.0));
    EXPECT_THAT(drives, ::testing::ElementsAre(DriveIs(1.02, 1.0, 0.0),
                                               DriveIs(1.02 + overdrive, kRated, 1e-9)));
}

TEST(DrivePlanner, OverdriveNeverOutlastsItsNoteNorTheModelsNeed) {
    // A note shorter than the overdrive it would need: full scale throughout, and no more.
    DrivePlanner planner(example_erm(), {});
    const double needed = kUp * std::log(kFull / (kFull - 1.0));
    EXPECT_THAT(plan(planner, 0.0, needed * 0.5, 1.0),
                ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0)));
    // The edge: an overdrive just above the shortest one backends resolve is kept ...
    const double min_pulse = PlannerOptions{}.min_pulse_s;
    const double just_above = kFull - (kFull - 0.5) * std::exp(-(min_pulse * 1.01) / kUp);
    DrivePlanner above(example_erm(), {});
    plan(above, 0.0, 1.0, 0.5);
    EXPECT_THAT(plan(above, 1.0, 2.0, just_above),
                ::testing::ElementsAre(DriveIs(1.0, 1.0, 0.0),
                                       DriveIs(1.0 + min_pulse * 1.01, just_above * kRated, 1e-9)));
    // ... one just below it goes straight to the hold.
    const double just_below = kFull - (kFull - 0.5) * std::exp(-(min_pulse * 0.99) / kUp);
    DrivePlanner below(example_erm(), {});
    plan(below, 0.0, 1.0, 0.5);
    EXPECT_THAT(plan(below, 1.0, 2.0, just_below),
                ::testing::ElementsAre(DriveIs(1.0, just_below * kRated, 0.0)));
}

TEST(DrivePlanner, NeverAboveFullScaleAndWhatIsOutOfReachIsDrivenFull) {
    DrivePlanner planner(example_erm(), {});
    EXPECT_THAT(plan(planner, 0.0, 1.0, 2.0), ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0)));
    // The last strength full scale holds is reached, and held at full scale.
    DrivePlanner edge(example_erm(), {});
    const auto drives = plan(edge, 0.0, 1.0, kFull);
    for (const auto& cue : drives) {
        EXPECT_LE(std::abs(cue.amplitude), 1.0);
    }
}

TEST(DrivePlanner, AnEndIsBrakedBackwardsForExactlyAsLongAsItTakesToStop) {
    DrivePlanner planner(example_erm(), {.reverse = true});
    plan(planner, 0.0, 1.0, 1.0);
    const auto drives = plan(planner, 1.0, INFINITY, 0.0);
    const double brake = kUp * std::log((1.0 + kFull) / kFull);
    EXPECT_THAT(drives,
                ::testing::ElementsAre(DriveIs(1.0, -1.0, 0.0), DriveIs(1.0 + brake, 0.0, 1e-9)));
}

TEST(DrivePlanner, AFallIsBrakedToTheWrittenLevelThenHeld) {
    DrivePlanner planner(example_erm(), {.reverse = true});
    plan(planner, 0.0, 1.0, 1.0);
    const auto drives = plan(planner, 1.0, 2.0, 0.5);
    const double brake = kUp * std::log((1.0 + kFull) / (0.5 + kFull));
    EXPECT_THAT(drives, ::testing::ElementsAre(DriveIs(1.0, -1.0, 0.0),
                                               DriveIs(1.0 + brake, 0.5 * kRated, 1e-9)));
}

TEST(DrivePlanner, WithoutReverseAFallCoastsToTheWrittenLevel) {
    DrivePlanner planner(example_erm(Brake::none), {.reverse = false});
    plan(planner, 0.0, 1.0, 1.0);
    const auto drives = plan(planner, 1.0, 2.0, 0.5);
    EXPECT_THAT(drives, ::testing::ElementsAre(DriveIs(1.0, 0.0, 0.0),
                                               DriveIs(1.0 + kDown * std::log(2.0), 0.35, 1e-9)));
}

TEST(DrivePlanner, WithoutReverseANoteEndsEarlySoItsFeltEndIsOnTime) {
    DrivePlanner planner(example_erm(Brake::none), {.reverse = false});
    const auto drives = plan(planner, 0.0, 1.0, 1.0, 0.0, true);
    // Long enough to settle: the drive stops spin-down x ln 2 early, so the strength is half the
    // written one exactly at the written end.
    ASSERT_EQ(drives.size(), 3u);
    EXPECT_NEAR(drives[2].at, 1.0 - kDown * std::log(2.0), 1e-9);
    EXPECT_EQ(drives[2].amplitude, 0.0);
    EXPECT_NEAR(strength_at(example_erm(Brake::none), drives, 1.0), 0.5, 1e-5);
    EXPECT_NEAR(Physics::strength(planner.carry().state), 0.5, 1e-9);
}

TEST(DrivePlanner, ANoteTooShortToLingerKeepsAllItsDrive) {
    DrivePlanner planner(example_erm(Brake::none), {.reverse = false});
    // 5 ms at full scale from rest: strength 0.16 at the end, below half of 1.
    EXPECT_THAT(plan(planner, 0.0, 0.005, 1.0, 0.0, true),
                ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0)));
}

TEST(DrivePlanner, WithReverseANoteKeepsItsDriveToTheWrittenEnd) {
    DrivePlanner planner(example_erm(), {.reverse = true});
    const auto drives = plan(planner, 0.0, 1.0, 1.0, 0.0, true);
    EXPECT_EQ(drives.size(), 2u);
    EXPECT_EQ(drives.back().amplitude, kRated);
}

TEST(DrivePlanner, AnLraIsDrivenHarderAwayFromItsResonanceAsFarAsItsBeatAllows) {
    // Off resonance the strength beats on its way to where the hold settles it: the hold is as
    // strong as keeps the beat's top at the strength, harder than off's and no harder than
    // settles it there.
    DrivePlanner planner(example_lra(), {});
    const auto drives = plan(planner, 0.0, 1.0, 0.5, 181.0);
    const double gain = Physics::lra_gain(181.0, 175.0, 15.0);
    EXPECT_GT(planner.carry().drive.amplitude, 0.5 * kRated * 1.3);
    EXPECT_LE(planner.carry().drive.amplitude, 0.5 * kRated / gain + 1e-12);
    EXPECT_EQ(planner.carry().drive.frequency_hz, 181.0);
    const Physics lra(example_lra());
    double highest = 0.0;
    State state;
    for (std::size_t i = 0; i < drives.size(); ++i) {
        const double next = i + 1 < drives.size() ? drives[i + 1].at : 1.0;
        const actuator::Drive drive{drives[i].amplitude, drives[i].frequency_hz};
        for (int k = 1; k <= 2000; ++k) {
            highest = std::max(highest, Physics::strength(lra.advance(
                                            state, drive, (next - drives[i].at) * k / 2000.0)));
        }
        state = lra.advance(state, drive, next - drives[i].at);
    }
    // A thousandth of rated strength above (a hairpin's steps), and a hair for the points at
    // which the planner looks at the beat (96 over three time constants).
    EXPECT_LE(highest, 0.5 + 0.001 + 1e-5);
    EXPECT_GT(Physics::strength(planner.carry().state), 0.9 * 0.5);
    // Beyond what full scale gives there: full scale, and the strength stays short.
    DrivePlanner far(example_lra(), {});
    plan(far, 0.0, 1.0, 0.5, 235.0);
    EXPECT_EQ(far.carry().drive.amplitude, 1.0);
}

TEST(DrivePlanner, AnLraIsBrakedInAntiPhaseAtItsOwnFrequency) {
    DrivePlanner planner(example_lra(), {.reverse = true});
    plan(planner, 0.0, 1.0, 1.0, 175.0);
    const auto drives = plan(planner, 1.0, INFINITY, 0.0, 0.0);
    const double brake = kTau * std::log((1.0 + kFull) / kFull);
    ASSERT_THAT(drives,
                ::testing::ElementsAre(DriveIs(1.0, -1.0, 0.0), DriveIs(1.0 + brake, 0.0, 1e-6)));
    EXPECT_EQ(drives[0].frequency_hz, 175.0);
}

// --- Issue 32: compensation that is never worse than none -------------------------------------
// Judged by bench/feel's plant (bench/feel_plant: the resonator's differential equation
// integrated step by step), not by the closed forms the planner plans with.

// Notes (strength, frequency), each `length` long and followed by as much silence, and the
// plant's strength under their drives (bench/note_phrases, which bench/planner_search draws
// phrases of at random).
using bench::Artefacts;
using bench::artefacts;
using bench::play_notes;
using bench::Played;
constexpr double kPlantRate = bench::kPhraseRate;

TEST(DrivePlanner, WithTheDeclarationRightNoNoteOvershootsOrRisesAgainAfterItsEnd) {
    // An LRA's notes across its band, to its edges (f0 -+ f0 / 2Q, where it gives 1/sqrt 2 of its
    // strength), weak and strong, each 150 ms and 150 ms of silence: on the plant, no note goes
    // more than 5 % above its strength, and none rises again above 10 % of it once stopped.
    const Declaration lra = example_lra();
    const double edge = 175.0 / (2.0 * 15.0);
    const std::vector<std::pair<double, double>> notes{{1.0, 175.0},
                                                       {0.4, 175.0 - edge},
                                                       {0.8, 175.0 + edge},
                                                       {0.6, 175.0 - 0.5 * edge},
                                                       {0.5, 175.0 + 0.5 * edge},
                                                       {0.2, 175.0}};
    const auto played =
        play_notes(lra, lra, {.reverse = true, .uncertainty = kPartToPart}, notes, 0.150);
    const Artefacts worst = artefacts(played, notes, 0.150);
    EXPECT_LE(worst.overshoot, 0.05);
    EXPECT_LE(worst.rebound, 0.10);
}

TEST(DrivePlanner, PlannedAsExactNoNoteFarFromTheResonanceOvershootsEither) {
    // Declared with no tolerance (an admin's choice) the same holds, out to notes 9-14 % off the
    // resonance: a hold that settles off resonance beats above the strength on the way (up to
    // 35 % on bench/feel's 170 Hz score before), so it is lowered until the beat's top is there.
    const Declaration lra = example_lra();
    const std::vector<std::pair<double, double>> notes{{0.5, 155.0}, {0.8, 190.0}, {0.4, 160.0},
                                                       {0.9, 200.0}, {0.6, 181.0}, {1.0, 175.0}};
    const auto played = play_notes(lra, lra, {.reverse = true}, notes, 0.150);
    const Artefacts worst = artefacts(played, notes, 0.150);
    EXPECT_LE(worst.overshoot, 0.05);
    EXPECT_LE(worst.rebound, 0.10);
}

TEST(DrivePlanner, ALowQLrasNotesFarFromItsResonanceDoNotRiseAgainAfterTheirBrake) {
    // A low-Q LRA braked far off its resonance at full scale rang on with what the planner's
    // envelope model leaves out (Physics::unmodelled_kick): 21 % of the note on the plant here.
    // Planned as exact, and with the margins of part-to-part spread (which brakes with the
    // robust brake), a Q-8 LRA's notes up to 20 % off the resonance, at three lengths (three
    // phases of the drive at each switch): none rises again above 10 % nor overshoots by 5 %.
    // (The robust brake left 10.8 % here until its brakes were watched for the ripple:
    // ARobustBrakeIsWatchedFinely... below.)
    const Declaration lra = example_lra(175.0, 8.0);
    const std::vector<std::pair<double, double>> notes{{0.7, 140.0}, {0.5, 210.0}, {0.9, 150.0},
                                                       {0.7, 200.0}, {0.4, 160.0}, {0.8, 190.0},
                                                       {0.6, 175.0}};
    for (const Uncertainty margins : {Uncertainty{}, kPartToPart}) {
        for (const double length : {0.100, 0.1013, 0.1027}) {
            const auto played =
                play_notes(lra, lra, {.reverse = true, .uncertainty = margins}, notes, length);
            const Artefacts worst = artefacts(played, notes, length);
            EXPECT_LE(worst.rebound, 0.10) << length << " margins " << margins.resonance;
            EXPECT_LE(worst.overshoot, 0.05) << length << " margins " << margins.resonance;
        }
    }
}

TEST(DrivePlanner, AnOverdriveStartingWhereLittleRingsOvershootsAtNoPhaseOfItsCarrier) {
    // Six notes found by a random search (175 Hz Q-8 LRA, part-to-part margins): the last, 0.69
    // at 199 Hz 33 ms after a brake far off resonance, went 5.6 % above its strength on the
    // plant where the whole motion said 1.3 %. What the brake left rang in each followed motion
    // at about the phase its last start gave it, so meeting it at k / 24 of a turn from there
    // tried one phase of the carrier 24 times; the carrier's own phases are now tried too.
    const Declaration lra = example_lra(175.0, 8.0);
    const std::vector<std::pair<double, double>> notes{
        {0.38993824406518474, 185.93277273968641}, {0.76546841153375145, 189.75018008204597},
        {0.33702380905531454, 183.01762291350599}, {0.42514595721410009, 183.41564297900308},
        {0.98272871522071492, 155.64530642583725}, {0.6948025645562127, 198.54576823176035}};
    const double length = 0.043006162905937576;
    const auto played =
        play_notes(lra, lra, {.reverse = true, .uncertainty = kPartToPart}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).overshoot, 0.05);
}

TEST(DrivePlanner, NoBrakeDrivesTheLraOnPastWhereItStarted) {
    // Found by a random search (a 150 Hz Q-25 LRA planned as exact, notes up to 15 % off its
    // resonance): the fifth note, 0.37 at 171 Hz, was braked at 168 Hz for the whole silence
    // after it, which the envelope said brought it to rest; by the whole motion the brake drove
    // it on, to 0.43 when the last note (0.36 at 141 Hz) started, which went 37 % above. A brake
    // whose whole motion rises more than a tenth above where it started is not taken.
    const Declaration lra = example_lra(150.0, 25.0);
    const std::vector<std::pair<double, double>> notes{
        {0.33809932974054102, 156.78512669386521}, {0.32813518039595257, 137.76294123239342},
        {0.62018817445966667, 140.30160408584038}, {0.81015284941922339, 139.86482199694555},
        {0.36731436684123586, 171.3232598843806},  {0.36270933508779135, 140.57076463144489}};
    const double length = 0.026631409135763562;
    const auto played = play_notes(lra, lra, {.reverse = true}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).overshoot, 0.05);
    const auto start = static_cast<std::size_t>(10.0 * length * kPlantRate);
    EXPECT_LT(played.strength[start], notes[4].first);
}

TEST(DrivePlanner, ANoteStartingWhereEarlierNotesStillRingIsJudgedMeetingThemAtTheWorstPhase) {
    // Found by a random search (a 175 Hz Q-15 LRA planned with calibrate's margins, notes up to
    // 15 % off its resonance): the last note, 0.45 at 151 Hz, started where 13 % of it still
    // rang from the notes before, each of which had started at a phase of its own. Followed as
    // if every note had started at the same phase, that ringing was weaker than bench/feel's
    // plant's, and the note went 7.6 % above its strength.
    const Declaration lra = example_lra(175.0, 15.0);
    const std::vector<std::pair<double, double>> notes{
        {0.41838262356802891, 149.39083902550547}, {0.85506019253213927, 154.94013394062981},
        {0.79266624654879758, 200.46874364902337}, {0.8259780466873532, 178.85580882278094},
        {0.9332001359792903, 175.51902138315441},  {0.44997739207679188, 150.88178288445175}};
    const double length = 0.03237561168517919;
    const auto played =
        play_notes(lra, lra, {.reverse = true, .uncertainty = {0.01, 0.15}}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).overshoot, 0.05);
}

TEST(DrivePlanner, ABrakeIsJudgedAgainstTheRingingEarlierNotesLeftAtEveryPhase) {
    // Found by a random search (a 150 Hz Q-25 LRA planned as exact, notes up to 15 % off its
    // resonance): the third note, 0.32 at 140 Hz, started where a little of the 0.85 before it
    // still rang; its brake, judged by the whole motion with every note started at one phase,
    // left it at rest, but where the earlier ringing met it at another it rose again to 12.9 %.
    const Declaration lra = example_lra(150.0, 25.0);
    const std::vector<std::pair<double, double>> notes{
        {0.66340658345684433, 148.48249660837561}, {0.84530070575184801, 140.60926777568352},
        {0.32368200697411337, 140.14207795850484}, {0.95109427064480268, 142.50120178707141},
        {0.36116453543330768, 135.52842038449486}, {0.66287688743640494, 134.85391497158486}};
    const double length = 0.035009580442206131;
    const auto played = play_notes(lra, lra, {.reverse = true}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).rebound, 0.10);
}

TEST(DrivePlanner, ABrakeLongerThanItsSilenceIsJudgedWhereTheNextNoteCutsIt) {
    // A random search's draw (a 150 Hz Q-25 LRA planned as exact): the envelope took 88 ms to
    // bring the third note (0.53 at 163 Hz) to rest under a brake at 161 Hz, so the brake was
    // judged over 88 ms; the next note cut it after 33, where it had driven the LRA on (0.33,
    // where coasting leaves 0.28), and that note went 93 % above its strength.
    const Declaration lra = example_lra(150.0, 25.0);
    const std::vector<std::pair<double, double>> notes{
        {0.7087993373274204, 170.57504899195209},  {0.56614519561102616, 169.28324189805221},
        {0.53364579873916851, 163.06993281485686}, {0.30673695405406431, 164.40781772195996},
        {0.42008330955004181, 153.90841647692918}, {0.83011427948402638, 152.45885279549131}};
    const double length = 0.033387180768699315;
    const auto played = play_notes(lra, lra, {.reverse = true}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).overshoot, 0.05);
}

TEST(DrivePlanner, ABrakeIsJudgedAtPhasesCloseEnoughThatNoneDipsAndRisesBetweenThem) {
    // A random search's draw (a 235 Hz Q-8 LRA planned as exact): the last note, 0.55 at 263 Hz,
    // braked a quarter of full scale at 202 Hz, dipped below 10 % and rose again to 10.9 % at a
    // phase of its start between two of the 24 the brake was judged at.
    const Declaration lra = example_lra(235.0, 8.0);
    const std::vector<std::pair<double, double>> notes{
        {0.76979845886736442, 221.63865525810121}, {0.69408315424700096, 262.77048605284142},
        {0.45890689406390223, 255.83301511571904}, {0.60214087864808041, 217.65202635625602},
        {0.63120415343779446, 205.84865152075292}, {0.55219059732339204, 263.29624920117698}};
    const double length = 0.052766696539811156;
    const auto played = play_notes(lra, lra, {.reverse = true}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).rebound, 0.10);
}

TEST(DrivePlanner, ABrakeIsLookedAtOftenEnoughToSeeTheTopOfEveryRipple) {
    // A random search's draw (a 175 Hz Q-25 LRA planned as exact): the fifth note, 0.74 at
    // 180 Hz, braked with the LRA looked at eight times a period of the ripple the brake makes
    // with its own ringing, rose again to 10.05 %, a ripple's top between two looks; sixteen see
    // it.
    const Declaration lra = example_lra(175.0, 25.0);
    const std::vector<std::pair<double, double>> notes{
        {0.94403866477523057, 193.4510978409123},  {0.36111780552727096, 169.79277852043617},
        {0.31780568303774076, 161.86969949327644}, {0.88464480683648805, 199.9662252651091},
        {0.74218188807173102, 180.30790599409843}, {0.84119810312898902, 176.53040552643958}};
    const double length = 0.072397798166601399;
    const auto played = play_notes(lra, lra, {.reverse = true}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).rebound, 0.10);
}

TEST(DrivePlanner, APhaseBetweenTwoJudgedThatDipsToQuietIsAsLoudAfterAsWhereItLiesBetweenThem) {
    // A random search's draw (a 175 Hz Q-8 LRA with the part-to-part margins): the last note,
    // 0.62 at 173 Hz, braked at 185 Hz, rose again to 10.2 % just after the brake at the phase
    // bench/feel's plant started it at, between the phase of the 96 judged that dipped below
    // 10 % (and stayed under it) and the one beside it that did not dip.
    const Declaration lra = example_lra(175.0, 8.0);
    const std::vector<std::pair<double, double>> notes{
        {0.84761545314774489, 154.28019583851159}, {0.47690146443155551, 200.79148256773036},
        {0.51915916420012698, 183.50497687174857}, {0.34661011249105195, 190.78493108577345},
        {0.8320104581063128, 159.60572424665941},  {0.62486362421874631, 173.45455001260186}};
    const double length = 0.062457038170433715;
    const auto played =
        play_notes(lra, lra, {.reverse = true, .uncertainty = kPartToPart}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).rebound, 0.10);
}

TEST(DrivePlanner, ATapAfterABrakedTapIsPushedToItsStrengthWhatLittleTheBrakeLeft) {
    // bench/feel's taps (ten 50 ms taps a second at 248 Hz) on a 235 Hz Q-8 LRA with the
    // part-to-part margins: each brake leaves a hair of the tap ringing in anti-phase, which the
    // next tap's push first takes down through its least. Every tap, not only the first, gets its
    // push and reaches 90 % of its strength (the nine after the first were held without it, at
    // 78 %).
    const Declaration lra = example_lra(235.0, 8.0);
    const std::vector<std::pair<double, double>> taps(10, {1.0, 248.22});
    const double length = 0.05;
    const auto played =
        play_notes(lra, lra, {.reverse = true, .uncertainty = kPartToPart}, taps, length);
    for (std::size_t i = 0; i < taps.size(); ++i) {
        const auto from =
            played.strength.begin() + static_cast<std::ptrdiff_t>(2.0 * length * i * kPlantRate);
        const double most =
            *std::max_element(from, from + static_cast<std::ptrdiff_t>(length * kPlantRate));
        EXPECT_GE(most, 0.9) << "tap " << i;
    }
}

TEST(DrivePlanner, AFallsBrakesLastWholeHalfCyclesSoTheyDoWhatTheEnvelopeSaysAtAnyPhase) {
    // bench/feel's notification-calendar, its last note, on a 150 Hz Q-25 LRA planned as exact:
    // a decrescendo at 149.46 Hz in steps of 5 ms, each fall braked. Braked for 0.5 ms every
    // 10 ms (a thirteenth of a cycle), the plant went 0.1 off the written strength (0.54 where
    // 0.44 was written). With the steps starting at eight phases of the note's carrier, it
    // follows the written strength closely at each.
    const Declaration lra = example_lra(150.0, 25.0);
    const double f = 149.46, step = 0.005, top = 0.9;
    const int steps = 80;
    const auto written = [&](int k) { return top * (1.0 - static_cast<double>(k) / steps); };
    for (int p = 0; p < 8; ++p) {
        const double held = 0.05 + p / (8.0 * f);
        DrivePlanner planner(lra, {.reverse = true});
        std::vector<Cue> drives;
        planner.segment(0.0, held, top, f, false, drives);
        for (int k = 0; k < steps; ++k) {
            const double at = held + k * step;
            planner.segment(at, at + step, written(k), f, k + 1 == steps, drives);
        }
        const auto plant = bench::Plant(lra).respond(
            drives, kPlantRate, static_cast<std::size_t>((held + steps * step) * kPlantRate));
        double furthest = 0.0;
        for (int k = 4; k < steps - 8; ++k) {
            const auto end = static_cast<std::size_t>((held + (k + 1) * step) * kPlantRate) - 1;
            furthest = std::max(furthest, std::abs(plant[end] - written(k)));
        }
        EXPECT_LE(furthest, 0.05 * top) << "steps from " << p << "/8 of a turn";
    }
}

TEST(DrivePlanner, ABrakeUpToFourHalfCyclesLongIsMadeWholeHalfCyclesAndLongerOnesAreNot) {
    // At resonance, from 0.8 held, full anti-phase (steady at -1 / rated) reaches s after
    // tau ln((0.8 + 1 / rated) / (s + 1 / rated)): the falls whose full brake lasts just under and
    // just over four half cycles of 175 Hz.
    const Declaration lra = example_lra(175.0, 15.0);
    const double f = 175.0, half = 0.5 / f, from = 0.8, reverse = 1.0 / kRated;
    for (const double halves : {3.96, 4.04}) {
        const double s = (from + reverse) * std::exp(-halves * half / kTau) - reverse;
        PlannerCarry carry;
        carry.state = {from, f};
        carry.drive = {from * kRated, f};
        carry.ringing_frequency_hz = f;
        DrivePlanner planner(lra, {.reverse = true}, carry);
        const auto drives = plan(planner, 0.0, 0.05, s, f);
        ASSERT_EQ(drives.size(), 2u) << halves;
        if (halves < 4.0) {
            EXPECT_NEAR(drives[1].at, 4.0 * half, 1e-12);
            EXPECT_GT(drives[0].amplitude, -1.0);
        } else {
            EXPECT_NEAR(drives[1].at, halves * half, 1e-9);
            EXPECT_EQ(drives[0].amplitude, -1.0);
        }
        // Either way it lands, by the model, where the full brake would have.
        const State landed = Physics(lra).advance(
            carry.state, {drives[0].amplitude, drives[0].frequency_hz}, drives[1].at);
        EXPECT_NEAR(Physics::strength(landed), s, 1e-3 * s) << halves;
    }
}

TEST(DrivePlanner, ABrakeNoWeakerWholeHalfCycleLandsWhereItShouldKeepsItsFullScale) {
    // Far off a Q-5 LRA's resonance (150 Hz on 175 Hz), from 0.6 at 3/16 of a turn off the
    // drive's phase, the full brake to 0.54 takes a sixth of a half cycle; a weaker brake over a
    // whole half cycle beats elsewhere and lands it at 0.54 at no strength. The brake is kept as
    // the envelope planned it, full scale, and lands there.
    const Declaration lra = example_lra(175.0, 5.0);
    const double f = 150.0, half = 0.5 / f, s = 0.54;
    PlannerCarry carry;
    carry.state = {std::polar(0.6, 2.0 * std::numbers::pi * 3.0 / 16.0), f};
    carry.drive = {0.5, f};
    carry.ringing_frequency_hz = f;
    DrivePlanner planner(lra, {.reverse = true}, carry);
    const auto drives = plan(planner, 0.0, 0.05, s, f);
    ASSERT_EQ(drives.size(), 2u);
    EXPECT_EQ(drives[0].amplitude, -1.0);
    EXPECT_LT(drives[1].at, half);
    const State landed = Physics(lra).advance(
        carry.state, {drives[0].amplitude, drives[0].frequency_hz}, drives[1].at);
    EXPECT_NEAR(Physics::strength(landed), s, 1e-6);
}

TEST(DrivePlanner, AnOverdriveOutOfABrakeMeetsWhatEarlierNotesLeftAtTheWorstPhase) {
    // A random search's draw (a 175 Hz Q-25 LRA planned as exact): the fifth note, 0.38 at
    // 174 Hz, was overdriven straight out of the brake of the note before (no new start: the
    // carrier goes on), where the notes before that still rang at phases of their own; judged
    // with every note started at one phase, it went 10.7 % above its strength.
    const Declaration lra = example_lra(175.0, 25.0);
    const std::vector<std::pair<double, double>> notes{
        {0.76068790115466944, 199.46041195108077}, {0.71978495519591912, 149.71403267474338},
        {0.31333449292160087, 166.28538729932887}, {0.77653127960669677, 189.46828077239502},
        {0.38222592720058479, 173.51863300072318}, {0.80846349516631233, 161.46106341021851}};
    const double length = 0.03067426476852991;
    const auto played = play_notes(lra, lra, {.reverse = true}, notes, length);
    EXPECT_LE(artefacts(played, notes, length).overshoot, 0.05);
}

TEST(DrivePlanner, ARobustBrakeIsWatchedFinelyEnoughToSeeItsRippleCrossTheQuietLevelAgain) {
    // Braked a little off its resonance, an LRA's strength falls with a ripple at the sum of the
    // brake's and its own frequencies (about 3 ms a period here). Watched only at a brake
    // search's looks (2 ms apart on a Q-25 LRA), a brake whose ripple fell below 10 % and rose
    // to 10.7 % between two of them was chosen (bench/feel's taps on a 175 Hz Q-25 LRA planned
    // with calibrate's margins). Ten taps at 178 Hz, three lengths: none rises again.
    const Declaration lra = example_lra(175.0, 25.0);
    const std::vector<std::pair<double, double>> notes(10, {1.0, 178.15});
    for (const double length : {0.050, 0.0507, 0.0513}) {
        const auto played =
            play_notes(lra, lra, {.reverse = true, .uncertainty = {0.01, 0.15}}, notes, length);
        EXPECT_LE(artefacts(played, notes, length).rebound, 0.10) << length;
    }
}

TEST(DrivePlanner, ABrakeForAnUncertainLraIsChosenByWhenItsWholeMotionFallsQuiet) {
    // Planned with calibrate's margins and declared right, a 60 ms note at the resonance falls
    // below a tenth of its strength on the plant within 30 % of the time coasting takes, on
    // LRAs across the band and the Qs. Chosen by the envelope's stop, 5 of these 32 took 32-45 %
    // (a 0.5 note on a 170 Hz Q-15 LRA 20.7 ms, where coasting takes 64.7): the envelope leaves
    // out the part of the motion that turns at the LRA's own frequency, which is what is left
    // where it says the brake has stopped it.
    for (const double f0 : {150.0, 170.0, 200.0, 235.0}) {
        for (const double q : {6.0, 10.0, 15.0, 25.0}) {
            for (const double s : {0.5, 1.0}) {
                const Declaration lra = example_lra(f0, q);
                const std::vector<std::pair<double, double>> note{{s, f0}};
                constexpr double kLength = 0.060;
                const auto played = play_notes(
                    lra, lra, {.reverse = true, .uncertainty = {0.01, 0.15}}, note, kLength);
                const auto end = static_cast<std::size_t>(kLength * kPlantRate);
                std::size_t last_loud = end;
                for (std::size_t k = end; k < played.strength.size(); ++k) {
                    if (played.strength[k] >= 0.1 * s) {
                        last_loud = k;
                    }
                }
                const double coasting = actuator::lra_time_constant_s(f0, q) * std::log(10.0);
                EXPECT_LE(static_cast<double>(last_loud - end) / kPlantRate, 0.3 * coasting)
                    << f0 << " Hz Q " << q << ", " << s;
            }
        }
    }
}

TEST(DrivePlanner, ALegatoLinesLastNoteIsJudgedByItsOwnStrengthAfterItsEnd) {
    // A full-strength note tied to one at half strength that silence follows, the second in
    // the 5 ms steps a glide comes in: once the LRA has fallen below 10 % of the 0.5 last
    // written, it does not rise above that again. Judged against the line's strongest (1.0),
    // the brake's watch let LRAs planned with calibrate's margins rise to 11-13 % of the 0.5
    // (and bench/feel's "failure" to 11.6 % of its glide's last note).
    struct Line {
        double resonance_hz, q, glide_to;  // the second note glides from the resonance to this
    };
    for (const Line line :
         {Line{150.0, 8.0, 150.0}, Line{175.0, 8.0, 175.0}, Line{150.0, 25.0, 135.0}}) {
        const Declaration lra = example_lra(line.resonance_hz, line.q);
        DrivePlanner planner(lra, {.reverse = true, .uncertainty = {0.01, 0.15}});
        std::vector<Cue> drives;
        planner.note_starts();
        planner.segment(0.0, 0.1, 1.0, line.resonance_hz, false, drives);
        planner.note_starts();
        constexpr int kSteps = 40;
        for (int k = 0; k < kSteps; ++k) {
            const double f =
                line.resonance_hz + (line.glide_to - line.resonance_hz) * (k + 0.5) / kSteps;
            planner.segment(0.1 + 0.005 * k, 0.1 + 0.005 * (k + 1), 0.5, f, k + 1 == kSteps,
                            drives);
        }
        planner.segment(0.3, INFINITY, 0.0, 0.0, false, drives);
        const auto strength = bench::Plant(lra).respond(drives, kPlantRate,
                                                        static_cast<std::size_t>(0.5 * kPlantRate));
        auto k = static_cast<std::size_t>(0.3 * kPlantRate);
        while (k < strength.size() && strength[k] >= 0.05) {
            ++k;
        }
        ASSERT_LT(k, strength.size()) << line.resonance_hz << " Hz Q " << line.q;
        EXPECT_LE(
            *std::max_element(strength.begin() + static_cast<std::ptrdiff_t>(k), strength.end()),
            0.05)
            << line.resonance_hz << " Hz Q " << line.q;
    }
}

TEST(DrivePlanner, ABrakeForAnUncertainLraPushesNoneWithinTheUncertaintyBackUpPastRest) {
    // Declared 175 Hz Q 15; built anywhere within +-2.5 % of that resonance and +-40 % of that Q
    // (at +-5 % it is not braked at all: the next test).
    // After a strong note, the brake may leave any of them ringing, but never drives one, after
    // it has got as low as it gets, back up by more than 40 % of where it was when the brake
    // began: the planner keeps 30 % by its model; the plant, braked at one frequency while it
    // rings at its own, goes up to a tenth further (38.6 % at 166.25 Hz, Q 9).
    const Declaration declared = example_lra();
    for (const double f : {0.975, 1.0, 1.025}) {
        for (const double q : {0.6, 1.0, 1.4}) {
            const Declaration truth = example_lra(175.0 * f, 15.0 * q);
            const auto played = play_notes(
                declared, truth, {.reverse = true, .uncertainty = Uncertainty{0.025, 0.4}},
                {{1.0, 175.0}}, 0.3);
            const auto end = static_cast<std::size_t>(0.3 * kPlantRate);
            const double start = played.strength[end];
            double lowest = start, pushed = 0.0;
            for (std::size_t k = end; k < played.strength.size(); ++k) {
                lowest = std::min(lowest, played.strength[k]);
                pushed = std::max(pushed, played.strength[k] - lowest);
            }
            EXPECT_LE(pushed, 0.4 * start) << truth.resonance_hz << " Hz, Q " << truth.q;
        }
    }
}

TEST(DrivePlanner, AnLraWhoseResonanceIsUncertainByMoreThanHalfItsBandwidthIsNotBraked) {
    // Q 10 at 175 Hz: a bandwidth of 17.5 Hz. Within +-5 % (8.75 Hz, half of it) the brake's
    // phase is known well enough; beyond, the drive ends early instead, as on a board that cannot
    // brake: so early that the LRA within the margins that lingers most (the lowest resonance at
    // the highest Q: it rings longest) coasts to half the written strength at the written end.
    const Declaration lra = example_lra(175.0, 10.0);
    const auto last_note = [&](const Uncertainty& u) {
        DrivePlanner planner(lra, {.reverse = true, .uncertainty = u});
        auto drives = plan(planner, 0.0, 0.3, 1.0, 175.0, true);
        const auto rest = plan(planner, 0.3, INFINITY, 0.0);
        drives.insert(drives.end(), rest.begin(), rest.end());
        return drives;
    };
    const auto braked = [](const std::vector<Cue>& drives) {
        return std::any_of(drives.begin(), drives.end(),
                           [](const Cue& c) { return c.amplitude < 0.0; });
    };
    EXPECT_TRUE(braked(last_note({0.05, 0.4})));  // the last resonance tolerance braked
    const auto coasted = last_note({0.0501, 0.4});
    EXPECT_FALSE(braked(coasted));
    ASSERT_GE(coasted.size(), 2u);
    EXPECT_EQ(coasted.back().amplitude, 0.0);
    EXPECT_LT(coasted.back().at, 0.3 - 1e-3);  // ended early
    double most = 0.0;
    for (const double f : {0.9499, 1.0, 1.0501}) {
        for (const double q : {0.6, 1.0, 1.4}) {
            const double left = strength_at(example_lra(175.0 * f, 10.0 * q), coasted, 0.3);
            EXPECT_LE(left, 0.5 + 0.01) << 175.0 * f << " Hz, Q " << 10.0 * q;
            most = std::max(most, left);
        }
    }
    EXPECT_NEAR(most, 0.5, 0.01);
    EXPECT_LT(strength_at(lra, coasted, 0.3), 0.5);  // the declared one, sooner
}

// The hold of a long note (its last drive) at `frequency`, planned with `u`.
double hold_of(const Uncertainty& u, double frequency, double strength = 0.8) {
    DrivePlanner planner(example_lra(), {.reverse = true, .uncertainty = u});
    const auto drives = plan(planner, 0.0, 1.0, strength, frequency);
    return drives.back().amplitude;
}

TEST(DrivePlanner, WithMarginsNoLraWithinThemIsHeldFurtherFromTheStrengthThanWithoutCompensation) {
    // Issue 32: compensation never worse than none. Off holds strength x rated drive, which an LRA
    // within the margins settles at strength x G; the boost may take the most responsive of them
    // no further above than that leaves it below, and no more than 3 % above where one is
    // resonant at the note (G = 1).
    constexpr double s = 0.8;
    for (const double f : {160.0, 170.0, 175.0, 180.0, 183.75, 183.76, 190.0, 200.0}) {
        const double hold = hold_of(kPartToPart, f, s);
        double most = 0.0;
        for (double r = 0.95; r <= 1.05 + 1e-9; r += 0.0025) {
            for (const double q : {9.0, 15.0, 21.0}) {
                const double g = Physics::lra_gain(f, 175.0 * r, q);
                const double held = hold / kRated * g;
                EXPECT_LE(std::abs(held - s), std::max(s * (1.0 - g), 0.03 * s) + 1e-9)
                    << f << " Hz on " << 175.0 * r << " Hz, Q " << q;
                most = std::max(most, held);
            }
        }
        // ... and it does boost as far as that allows (or to what the declared one needs).
        const double exact = hold_of({}, f, s);
        EXPECT_TRUE(std::abs(hold - exact) < 1e-9 || most > s * 1.0299) << f << " Hz";
    }
    // On the declared resonance nothing changes: the declared one is held at the strength.
    EXPECT_NEAR(hold_of(kPartToPart, 175.0, s), s * kRated, 1e-12);
    // Without margins the off-resonance boost is the declared one's alone (issue 22), as far as
    // its beat allows: more than with the margins.
    EXPECT_LE(hold_of({}, 180.0, s), s * kRated / Physics::lra_gain(180.0, 175.0, 15.0) + 1e-9);
    EXPECT_GT(hold_of({}, 180.0, s), hold_of(kPartToPart, 180.0, s));
}

TEST(DrivePlanner, AnOverdriveAfterASilenceKeepsWhatStillRingsBelowTheLimitWhateverItsPhase) {
    // The drive's phase after a silence is the backend's (gpio-lra starts each waveform afresh),
    // so what still rings from the last note may meet the next note's overdrive in any phase. As
    // the ringtone's twelfth note on bench/feel's plant: a 178 Hz note's ring-down under a note
    // at 176 Hz.
    constexpr double until = 0.17;
    const Physics lra(example_lra());
    // 3 % above by the model, and a hundredth of the strength: a soft note no more than a
    // strong one.
    int overdriven = 0;
    for (const double s : {0.9, 0.4}) {
        for (const double left : {0.05, 0.1, 0.13, 0.2, 0.3}) {
            for (int p = 0; p < 8; ++p) {
                PlannerCarry carry;
                carry.state = {std::polar(left, 2.0 * std::numbers::pi * p / 8.0), 178.15};
                carry.ringing_frequency_hz = 178.15;
                carry.members.assign(8, State{});
                DrivePlanner planner(example_lra(), {.uncertainty = kPartToPart}, carry);
                const auto drives = plan(planner, 0.0, until, s, 176.05);
                ASSERT_FALSE(drives.empty());
                overdriven += drives.front().amplitude == 1.0 ? 1 : 0;
                for (int k = 0; k < 16; ++k) {
                    State state{std::polar(left, 2.0 * std::numbers::pi * k / 16.0), 176.05};
                    double highest = 0.0;
                    for (std::size_t i = 0; i < drives.size(); ++i) {
                        const double next = i + 1 < drives.size() ? drives[i + 1].at : until;
                        const actuator::Drive drive{drives[i].amplitude, drives[i].frequency_hz};
                        for (int n = 1; n <= 200; ++n) {
                            highest = std::max(
                                highest, Physics::strength(lra.advance(
                                             state, drive, (next - drives[i].at) * n / 200.0)));
                        }
                        state = lra.advance(state, drive, next - drives[i].at);
                    }
                    EXPECT_LE(highest, 1.04 * s + 1e-9)
                        << "strength " << s << ", left " << left << " at " << p
                        << "/8 of a turn, met at " << k << "/16";
                }
            }
        }
    }
    EXPECT_GT(overdriven, 0) << "the test needs overdrives";
}

TEST(DrivePlanner, AFallToASofterStrengthIsBrakedOnlyWhereTheBrakesPhaseIsKnown) {
    // An LRA 5 % off rings up to 60 degrees from the model: anti-phase there pushes as much as it
    // stops, so where the resonance is that uncertain a fall coasts, as without compensation.
    const auto fall = [](const Uncertainty& u) {
        DrivePlanner planner(example_lra(), {.reverse = true, .uncertainty = u});
        plan(planner, 0.0, 0.3, 1.0, 175.0);
        return plan(planner, 0.3, 0.6, 0.3, 175.0);
    };
    const auto negative = [](const std::vector<Cue>& drives) {
        return std::any_of(drives.begin(), drives.end(),
                           [](const Cue& c) { return c.amplitude < 0.0; });
    };
    EXPECT_TRUE(negative(fall({})));             // exact: braked
    EXPECT_TRUE(negative(fall({0.033, 0.4})));   // 0.033 x Q 15 = 0.495: braked
    EXPECT_FALSE(negative(fall({0.034, 0.4})));  // 0.51: coasts
    EXPECT_FALSE(negative(fall(kPartToPart)));
}

TEST(DrivePlanner, AMeasuredLrasBrakeNeverBringsItBackOnceItHasStopped) {
    // Issue 32: after a note's end the response never rises again above 10 % of its strength.
    // With a calibration's margins the brake is robust to the LRAs within them; the declared one,
    // once below a tenth, it may not push back up above that (the planner keeps it to 7 % where
    // it looks, for what the model does not see).
    for (const double frequency : {160.0, 175.0, 190.0}) {
        DrivePlanner planner(example_lra(), {.reverse = true, .uncertainty = {0.01, 0.15}});
        auto drives = plan(planner, 0.0, 0.3, 1.0, frequency, true);
        const auto rest = plan(planner, 0.3, INFINITY, 0.0);
        ASSERT_TRUE(
            std::any_of(rest.begin(), rest.end(), [](const Cue& c) { return c.amplitude < 0.0; }))
            << frequency << " Hz: braked";
        drives.insert(drives.end(), rest.begin(), rest.end());
        const double rate = 1e5;
        const auto strength = produced_strength(example_lra(), drives, rate, 50000);
        const double start = strength[30000];
        bool stopped = false;
        double after = 0.0;
        for (std::size_t k = 30000; k < strength.size(); ++k) {
            stopped = stopped || strength[k] < 0.1 * start;
            if (stopped) {
                after = std::max(after, strength[k]);
            }
        }
        EXPECT_TRUE(stopped) << frequency << " Hz";
        EXPECT_LE(after, 0.1 * start) << frequency << " Hz";
    }
}

TEST(DrivePlanner, AnErmsExactPlansStopEveryMotorWithinThirtyPercentSoonerThanNone) {
    // Why an ERM's plans are not budgeted: planned for 40/80 ms, a motor with either time
    // constant 30 % off either way (the edges of issue 32's grid) still stops sooner after a
    // strong note than with compensation off, by the plant.
    const Declaration declared = example_erm();
    const auto stop_after = [](const Played& played, double end) {
        for (auto k = static_cast<std::size_t>(end * kPlantRate); k < played.strength.size(); ++k) {
            if (played.strength[k] < 0.1) {
                return static_cast<double>(k) / kPlantRate - end;
            }
        }
        return static_cast<double>(INFINITY);
    };
    for (const double up : {0.7, 1.0, 1.3}) {
        for (const double down : {0.7, 1.0, 1.3}) {
            Declaration truth = declared;
            truth.spin_up_s *= up;
            truth.spin_down_s *= down;
            const auto on = play_notes(declared, truth, {.reverse = true}, {{1.0, 0.0}}, 0.4);
            const auto off =
                play_notes(declared, truth, {.compensation = false}, {{1.0, 0.0}}, 0.4);
            EXPECT_LT(stop_after(on, 0.4), stop_after(off, 0.4))
                << truth.spin_up_s << " s / " << truth.spin_down_s << " s";
        }
    }
}

TEST(DrivePlanner, TheBrakeGetsShorterAsTheUncertaintyGrows) {
    std::vector<double> lengths;
    for (const Uncertainty u : {Uncertainty{0.0, 0.0}, Uncertainty{0.01, 0.1},
                                Uncertainty{0.025, 0.2}, Uncertainty{0.033, 0.4}}) {
        DrivePlanner planner(example_lra(), {.reverse = true, .uncertainty = u});
        plan(planner, 0.0, 0.3, 1.0, 175.0);
        const auto drives = plan(planner, 0.3, INFINITY, 0.0);
        ASSERT_EQ(drives.size(), 2u);
        ASSERT_LT(drives[0].amplitude, 0.0);
        lengths.push_back(drives[1].at - drives[0].at);
    }
    for (std::size_t i = 1; i < lengths.size(); ++i) {
        EXPECT_LE(lengths[i], lengths[i - 1] + 1e-9) << "uncertainty step " << i;
    }
    EXPECT_LT(lengths.back(), lengths.front());
}

// A decrescendo from 1 to 0.1 over `length` (steps 5 ms apart) at `frequency`, then silence,
// planned for `declared` and played on `truth`; with `look_ahead`, each step is shown the rest
// of the note (as ActuatorDrives does). How long after its end `truth` takes to fall below a
// tenth of its first step.
double decrescendo_stop(const Declaration& declared, const Declaration& truth,
                        const PlannerOptions& options, double frequency, double length,
                        bool look_ahead) {
    constexpr double kStep = 0.005;
    const auto steps = static_cast<std::size_t>(std::lround(length / kStep));
    std::vector<Written> note;
    for (std::size_t i = 0; i < steps; ++i) {
        const double strength = 1.0 - 0.9 * static_cast<double>(i) / static_cast<double>(steps - 1);
        note.push_back({kStep * static_cast<double>(i), kStep * static_cast<double>(i + 1),
                        strength, frequency});
    }
    DrivePlanner planner(declared, options);
    std::vector<Cue> drives;
    for (std::size_t i = 0; i < note.size(); ++i) {
        const Written& w = note[i];
        const bool last = i + 1 == note.size();
        planner.segment(w.at, w.until, w.strength, w.frequency_hz, last, drives,
                        look_ahead ? std::span<const Written>(note).subspan(i + 1)
                                   : std::span<const Written>{});
    }
    planner.segment(length, INFINITY, 0.0, 0.0, false, drives);
    const auto strength = bench::Plant(truth).respond(
        drives, kPlantRate, static_cast<std::size_t>((length + 0.3) * kPlantRate));
    for (auto k = static_cast<std::size_t>(length * kPlantRate); k < strength.size(); ++k) {
        if (strength[k] < 0.1) {
            return static_cast<double>(k) / kPlantRate - length;
        }
    }
    return INFINITY;
}

TEST(DrivePlanner, WithoutBrakingADecrescendoLeavesNoLraWithinTheMarginsRingingLongerThanOff) {
    // Issue 32: never worse than none. Where the phase is not known well enough to brake, a
    // note's drive ends early for the LRA that rings longest. A decrescendo's last steps are
    // weak: ending their drive early cannot undo what the strong first ones set ringing in an
    // LRA driven harder than suits it (the boost far off the declared resonance). Shown the
    // rest of the note, the planner ends its drive soon enough that no LRA at the margins'
    // corners and edges rings on longer than without compensation (bench/feel's touch-click:
    // 30.5 ms against 15.0 on a 166 Hz Q-21 LRA before).
    const Declaration declared = example_lra();
    const PlannerOptions on{.reverse = true, .uncertainty = kPartToPart};
    const PlannerOptions off{.compensation = false};
    // Within a millisecond: where off has stopped by the note's end, the planner's model of the
    // LRA (its envelope) leaves on ringing above the tenth for a few cycles at most.
    constexpr double kWithin = 0.001;
    int worse_without_look_ahead = 0;
    for (const double frequency : {185.0, 215.0, 235.0}) {
        for (const double length : {0.05, 0.1}) {
            for (const double f : {0.95, 1.0, 1.05}) {
                for (const double q : {0.6, 1.0, 1.4}) {
                    Declaration truth = declared;
                    truth.resonance_hz *= f;
                    truth.q *= q;
                    const double none =
                        decrescendo_stop(declared, truth, off, frequency, length, false);
                    EXPECT_LE(decrescendo_stop(declared, truth, on, frequency, length, true),
                              none + kWithin)
                        << frequency << " Hz for " << length << " s on " << truth.resonance_hz
                        << " Hz Q " << truth.q;
                    worse_without_look_ahead += decrescendo_stop(declared, truth, on, frequency,
                                                                 length, false) > none + kWithin
                                                    ? 1
                                                    : 0;
                }
            }
        }
    }
    EXPECT_GT(worse_without_look_ahead, 0) << "the test needs notes the look-ahead mends";
}

TEST(DrivePlanner, LooksAheadOnlyWhereANotesEndIsItsEarlyEnd) {
    // Eight time constants of the LRA within the margins that rings longest (166.25 Hz, Q 21);
    // nothing where it brakes, plans for the declared one alone, or does not compensate.
    const double longest = actuator::lra_time_constant_s(175.0 * 0.95, 15.0 * 1.4);
    EXPECT_NEAR(
        DrivePlanner(example_lra(), {.reverse = true, .uncertainty = kPartToPart}).look_ahead_s(),
        8.0 * longest, 1e-12);
    EXPECT_EQ(
        DrivePlanner(example_lra(), {.reverse = true, .uncertainty = {0.01, 0.15}}).look_ahead_s(),
        0.0);
    EXPECT_EQ(DrivePlanner(example_lra(), {.reverse = false}).look_ahead_s(), 0.0);
    EXPECT_EQ(DrivePlanner(example_lra(), {.compensation = false, .uncertainty = kPartToPart})
                  .look_ahead_s(),
              0.0);
}

TEST(DrivePlanner, TheUncertaintyIsRefusedBeyondItsLimits) {
    // Up to half the resonance and 90 % of Q (a member's Q stays positive); not a hair more.
    EXPECT_NO_THROW(DrivePlanner(example_lra(), {.uncertainty = {0.5, 0.9}}));
    EXPECT_THROW(DrivePlanner(example_lra(), {.uncertainty = {0.5001, 0.9}}),
                 std::invalid_argument);
    EXPECT_THROW(DrivePlanner(example_lra(), {.uncertainty = {0.5, 0.9001}}),
                 std::invalid_argument);
    EXPECT_THROW(DrivePlanner(example_lra(), {.uncertainty = {-0.0001, 0.0}}),
                 std::invalid_argument);
    EXPECT_NO_THROW(DrivePlanner(example_lra(), {.uncertainty = {0.0, 0.0}}));
}

TEST(DrivePlanner, TheScaleIsThePlaybacksIntensity) {
    DrivePlanner planner(example_erm(), {.scale = 0.5, .compensation = false});
    EXPECT_THAT(plan(planner, 0.0, 1.0, 1.0), ::testing::ElementsAre(DriveIs(0.0, 0.35, 0.0)));
}

// Whatever the envelope, on either kind, with or without reverse: every drive within full scale,
// in time order, backwards only with reverse, and no overdrive or brake carrying the actuator
// past the written strength (it ends where the model gets there, or at the segment's end).
TEST(DrivePlanner, KeepsItsLimitsOverAnyEnvelope) {
    std::mt19937 random(22);
    std::uniform_real_distribution<double> strength(0.0, 1.6), length(0.001, 0.15),
        frequency(150.0, 200.0);
    for (const Declaration& declared :
         {example_erm(Brake::reverse), example_erm(Brake::none),
          example_lra(175.0, 15.0, Brake::reverse), example_lra(175.0, 15.0, Brake::none)}) {
        const bool reverse = declared.brake == Brake::reverse;
        DrivePlanner planner(declared, {.reverse = reverse});
        const Physics physics(declared);
        double at = 0.0;
        double previous = 0.0;
        for (int i = 0; i < 400; ++i) {
            const double written = i % 3 == 0 ? 0.0 : strength(random);
            const double until = at + length(random);
            const double f = declared.kind == Kind::lra ? frequency(random) : 0.0;
            const auto before = planner.carry().state;
            const auto drives = plan(planner, at, until, written, f, i % 3 == 2);
            for (std::size_t k = 0; k < drives.size(); ++k) {
                const Cue& cue = drives[k];
                ASSERT_LE(std::abs(cue.amplitude), 1.0);
                ASSERT_TRUE(reverse || cue.amplitude >= 0.0);
                ASSERT_GE(cue.at, previous);
                ASSERT_LT(cue.at, until);
                previous = cue.at;
            }
            // A push (full scale either way) that the planner ends within the segment for the
            // hold has brought the strength to the written one, not beyond. (A drive that stops
            // instead ends a note early: the felt end.)
            const double hold = std::min(1.0, physics.amplitude_for(written, f));
            if (drives.size() == 2 && std::abs(drives[0].amplitude) == 1.0 && drives[0].at == at &&
                std::abs(drives[1].amplitude - hold) < 1e-12) {
                const auto state = physics.advance(
                    before, {drives[0].amplitude, drives[0].frequency_hz}, drives[1].at - at);
                const double reached = Physics::strength(state);
                const double target = std::min(written, physics.steady_strength({1.0, f}));
                if (declared.kind == Kind::erm) {
                    EXPECT_NEAR(reached, written, 1e-6) << "segment " << i;
                } else if (written > 0.0 && drives[0].amplitude > 0.0) {
                    EXPECT_LE(reached, std::max(target, written) + 1e-6) << "segment " << i;
                } else if (written > 0.0) {
                    // A brake stops where it stops helping: never below the written strength.
                    EXPECT_GE(reached, written - 1e-6) << "segment " << i;
                } else {
                    // To rest: exactly, or (no brake frequency nulls it) as low as it gets.
                    EXPECT_LT(reached, Physics::strength(before)) << "segment " << i;
                }
            }
            at = until;
        }
    }
}

// The stage in the pipeline: what the player receives for a score.
CueAdaptation declared(const Declaration& d, bool reverse = true) {
    CueAdaptation adaptation;
    adaptation.actuator = d;
    adaptation.reverse = reverse;
    return adaptation;
}

Cue drive(double at, double amplitude, double frequency_hz = 0.0) {
    return drive_at(at, amplitude, frequency_hz);
}

Cue position(double at, std::size_t symbol) {
    Cue cue;
    cue.at = at;
    cue.kind = Cue::Kind::position;
    cue.symbol = symbol;
    return cue;
}

// A one-bar score on a sine clef (tempo 0.2 s; strings 170-180 Hz, inside the LRA's band;
// numbers 0.5 and 1) as the declared actuator produces it with compensation, sampled at 1 kHz.
struct Felt {
    std::vector<double> written, produced;
};
Felt felt(const std::string& notes, const Declaration& declared) {
    const auto bundle = testing::bundle_from(
        testing::one_clef_score("<Bar clef=\"c\">" + notes + "</Bar>"),
        {{"c.xml", testing::sine_clef(0.2, {170.0, 175.0, 180.0}, {0.5, 1.0})}});
    const Performance performance(bundle);
    ResponseOptions options;
    options.tail_s = 0.1;
    const auto response = actuator_response(performance, declared, options);
    return {response.written, response.compensated};
}

double lowest(const std::vector<double>& values, std::size_t from, std::size_t to) {
    return *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(from),
                             values.begin() + static_cast<std::ptrdiff_t>(to));
}

TEST(ActuatorDrives, LegatoAndPortamentoStayContinuousWhileTheDefaultSilenceIsFelt) {
    for (const Declaration& declared : {example_erm(), example_lra()}) {
        // Two quarter notes (200 ms each) from strength 1 to 0.5: tied, glided, or separated by
        // the default silence (30 ms at the first note's end).
        const auto legato = felt(
            "<Note length=\"quarter\" number=\"2\" string=\"2\" legato=\"1\"/>"
            "<Note length=\"quarter\" number=\"1\" string=\"3\" legato=\"1\"/>",
            declared);
        const auto glide = felt(
            "<Note length=\"quarter\" number=\"2\" string=\"1\" portamento=\"1\"/>"
            "<Note length=\"quarter\" number=\"1\" string=\"3\" portamento=\"1\"/>",
            declared);
        const auto apart = felt(
            "<Note length=\"quarter\" number=\"2\" string=\"2\"/>"
            "<Note length=\"quarter\" number=\"1\" string=\"3\"/>",
            declared);
        // Around the change (150..250 ms): tied notes never fall much below the lower level (the
        // glide's strings off the declared resonance are held no higher than an LRA within the
        // default margins resonant there allows: 0.39 at 170 Hz) ...
        EXPECT_GT(lowest(legato.produced, 150, 250), 0.35);
        EXPECT_GT(lowest(glide.produced, 150, 250), 0.35);
        // ... the untied ones dip to less than half of the weaker note: a felt silence.
        EXPECT_LT(lowest(apart.produced, 150, 250), 0.25);
    }
}

TEST(ActuatorDrives, AHairpinIsFollowedStepByStep) {
    // A crescendo from silence to 1 over a half note (400 ms), then a decrescendo back to
    // silence over another: once the actuator has caught up (20 ms), it stays within a few
    // hundredths of the written ramp.
    for (const Declaration& declared : {example_erm(), example_lra()}) {
        const auto hairpin = felt(
            "<Note length=\"half\" number=\"2\" string=\"2\" dynamics=\"crescendo\" "
            "legato=\"1\"/>"
            "<Note length=\"half\" number=\"2\" string=\"2\" dynamics=\"decrescendo\" "
            "legato=\"1\"/>",
            declared);
        double worst = 0.0;
        for (std::size_t k = 20; k < 780; ++k) {
            worst = std::max(worst, std::abs(hairpin.produced[k] - hairpin.written[k]));
        }
        EXPECT_LT(worst, 0.05);
    }
}

TEST(ActuatorDrives, BrakeOnlyWhereTheBackendCanAndTheBoardIsDeclaredTo) {
    const std::vector<Cue> note{drive(0.0, 1.0), drive(0.5, 0.0)};
    const auto has_negative = [](const std::vector<Cue>& cues) {
        return std::any_of(cues.begin(), cues.end(), [](const Cue& c) { return c.amplitude < 0; });
    };
    EXPECT_TRUE(has_negative(adapt_cues(note, 1.0, declared(example_erm(Brake::reverse), true))));
    EXPECT_FALSE(has_negative(adapt_cues(note, 1.0, declared(example_erm(Brake::reverse), false))));
    EXPECT_FALSE(has_negative(adapt_cues(note, 1.0, declared(example_erm(Brake::none), true))));
}

TEST(ActuatorDrives, TheUncertaintyReachesThePlanner) {
    // An LRA's note at its resonance, braked: exactly as the model needs when declared exact, for
    // less long the wider the margins (with the part-to-part ones, 5 % of a Q-15 LRA, not at
    // all).
    const std::vector<Cue> note{drive(0.0, 1.0, 175.0), drive(0.3, 0.0)};
    const auto brake_length = [&](const Uncertainty& uncertainty) {
        CueAdaptation adaptation = declared(example_lra(), true);
        adaptation.uncertainty = uncertainty;
        const auto cues = adapt_cues(note, 1.0, adaptation);
        const auto brake =
            std::find_if(cues.begin(), cues.end(), [](const Cue& c) { return c.amplitude < 0.0; });
        return brake != cues.end() && brake + 1 != cues.end() ? (brake + 1)->at - brake->at : 0.0;
    };
    EXPECT_NEAR(brake_length({}), kTau * std::log((1.0 + kFull) / kFull), 1e-6);
    double longest = brake_length({});
    for (const Uncertainty u :
         {Uncertainty{0.01, 0.15}, Uncertainty{0.025, 0.2}, Uncertainty{0.025, 0.4}}) {
        const double length = brake_length(u);
        EXPECT_GT(length, 0.0) << u.resonance << ", " << u.q;
        EXPECT_LE(length, longest) << u.resonance << ", " << u.q;
        longest = length;
    }
    EXPECT_LT(brake_length({0.025, 0.4}), brake_length({}) - 1e-3);
    EXPECT_EQ(brake_length(kPartToPart), 0.0);
}

TEST(ActuatorDrives, ADeclarationsTolerancesAreTheUncertaintyUnlessTheAdaptationGivesOne) {
    const std::vector<Cue> note{drive(0.0, 1.0, 175.0), drive(0.3, 0.0)};
    const auto cues_for = [&](const actuator::Declaration& lra,
                              std::optional<Uncertainty> uncertainty) {
        CueAdaptation adaptation = declared(lra, true);
        adaptation.uncertainty = uncertainty;
        return adapt_cues(note, 1.0, adaptation);
    };
    const auto same = [](const std::vector<Cue>& a, const std::vector<Cue>& b) {
        return a.size() == b.size() &&
               std::equal(a.begin(), a.end(), b.begin(), [](const Cue& x, const Cue& y) {
                   return x.at == y.at && x.amplitude == y.amplitude &&
                          x.frequency_hz == y.frequency_hz;
               });
    };
    actuator::Declaration lra = example_lra();
    EXPECT_EQ(uncertainty_of(lra), kPartToPart);  // [actuator]'s defaults
    EXPECT_TRUE(same(cues_for(lra, std::nullopt), cues_for(lra, kPartToPart)));
    EXPECT_FALSE(same(cues_for(lra, std::nullopt), cues_for(lra, Uncertainty{})));
    lra.resonance_tolerance = 0.0;
    lra.q_tolerance = 0.0;
    EXPECT_TRUE(same(cues_for(lra, std::nullopt), cues_for(lra, Uncertainty{})));
    lra.resonance_tolerance = 0.01;
    lra.q_tolerance = 0.15;
    EXPECT_EQ(uncertainty_of(lra), (Uncertainty{0.01, 0.15}));
    EXPECT_TRUE(same(cues_for(lra, std::nullopt), cues_for(lra, Uncertainty{0.01, 0.15})));
    EXPECT_EQ(uncertainty_of(example_erm()), Uncertainty{});  // an ERM's plans are not budgeted
}

TEST(ActuatorDrives, PositionsStayInTimeOrderAmongThePlannedDrives) {
    const auto cues =
        adapt_cues({drive(0.0, 1.0), position(0.0, 0), drive(0.2, 0.0), position(0.2, 1),
                    position(0.3, 2), drive(0.3, 0.8), drive(0.5, 0.0)},
                   0.5, declared(example_erm()));
    EXPECT_TRUE(std::is_sorted(cues.begin(), cues.end(),
                               [](const Cue& a, const Cue& b) { return a.at < b.at; }));
    EXPECT_EQ(std::count_if(cues.begin(), cues.end(),
                            [](const Cue& c) { return c.kind == Cue::Kind::position; }),
              3);
}

TEST(ActuatorDrives, OnlyTheLastPassBrakesBeyondItsEndAndTheNextPassGoesOnFromThere) {
    const std::vector<Cue> note{drive(0.0, 1.0), drive(0.1, 0.0)};  // ends where the pass ends
    auto carry = std::make_shared<PlannerCarry>();
    const auto first = adapt_cues(note, 0.1, declared(example_erm()));
    EXPECT_GT(first.back().at, 0.1);  // one pass, the last: the brake runs on after it

    AdaptedCueStream repeated(
        std::make_unique<CueListStream>(std::make_shared<const std::vector<Cue>>(note)), 0.1,
        declared(example_erm()), PassLink{carry, false});
    const auto pass = collect(repeated);
    for (const Cue& cue : pass) {
        EXPECT_LT(cue.at, 0.1);
    }
    EXPECT_NEAR(Physics::strength(carry->state), 1.0, 0.05);  // still spinning into the next pass

    // The next pass starts with a rest: it brakes what the last one left spinning.
    AdaptedCueStream next(std::make_unique<CueListStream>(std::make_shared<const std::vector<Cue>>(
                              std::vector<Cue>{drive(0.2, 1.0), drive(0.3, 0.0)})),
                          0.3, declared(example_erm()), PassLink{carry, true});
    const auto after = collect(next);
    ASSERT_FALSE(after.empty());
    EXPECT_EQ(after.front().at, 0.0);
    EXPECT_EQ(after.front().amplitude, -1.0);
}

TEST(ActuatorDrives, OnOffActuatorsGetOverdriveAndTheEarlyEndAsPulses) {
    CueAdaptation adaptation = declared(example_erm(Brake::none), false);
    adaptation.amplitude = false;
    const auto cues = adapt_cues({drive(0.0, 0.5), drive(0.4, 0.0)}, 0.4, adaptation);
    ASSERT_GE(cues.size(), 3u);
    // On without a break for the overdrive, longer than the first pulse of 0.35 x 40 ms would be.
    EXPECT_EQ(cues[0].amplitude, 1.0);
    EXPECT_GT(cues[1].at, 0.35 * 0.040);
    for (const auto& cue : cues) {
        EXPECT_TRUE(cue.amplitude == 0.0 || cue.amplitude == 1.0);
    }
    // The pulses stop early, spin-down x ln 2 before the written end (within the last pulse
    // period): the felt end is on time.
    const double cut = 0.4 - kDown * std::log(2.0);
    EXPECT_EQ(cues.back().amplitude, 0.0);
    EXPECT_LE(cues.back().at, cut + 1e-9);
    EXPECT_GT(cues.back().at, cut - adaptation.pulse_period_s);
}

// A stream over a list that remembers how far it has been read.
class ReadCounting final : public CueStream {
  public:
    explicit ReadCounting(std::vector<Cue> cues) : cues_(std::move(cues)) {}
    std::optional<Cue> next() override {
        if (next_ == cues_.size()) {
            return std::nullopt;
        }
        furthest_ = cues_[next_].at;
        return cues_[next_++];
    }
    double furthest() const { return furthest_; }
    bool done() const { return next_ == cues_.size(); }

  private:
    std::vector<Cue> cues_;
    std::size_t next_ = 0;
    double furthest_ = -1.0;
};

// A decrescendo from 1 to 0.1 at `frequency` in steps 5 ms apart, `length` long, then silence.
std::vector<Cue> decrescendo(double length, double frequency) {
    std::vector<Cue> cues;
    const auto steps = static_cast<int>(std::lround(length / 0.005));
    for (int i = 0; i < steps; ++i) {
        cues.push_back(drive(0.005 * i, 1.0 - 0.9 * i / (steps - 1.0), frequency));
    }
    cues.push_back(drive(length, 0.0));
    return cues;
}

TEST(ActuatorDrives, ANoteIsReadAheadAsFarAsThePlannerLooksForItsEndAndNoFurther) {
    // How much further than the drive after it the input had been read when each drive came out
    // (a drive goes on once the next one is known): the most, over a 2 s decrescendo.
    const auto read_beyond = [](const Uncertainty& uncertainty) {
        auto input = std::make_unique<ReadCounting>(decrescendo(2.0, 175.0));
        const ReadCounting& read = *input;
        CueAdaptation adaptation = declared(example_lra(), true);
        adaptation.uncertainty = uncertainty;
        AdaptedCueStream stream(std::move(input), 2.0, adaptation);
        std::vector<std::pair<double, double>> made;  // (at, read to)
        while (const auto cue = stream.next()) {
            made.emplace_back(cue->at, read.furthest());
        }
        EXPECT_TRUE(read.done());
        double most = -INFINITY;
        for (std::size_t k = 0; k + 1 < made.size(); ++k) {
            most = std::max(most, made[k].second - made[k + 1].first);
        }
        return most;
    };
    // Within the default margins (no braking): eight time constants of the LRA that rings
    // longest, and the step after.
    const double ahead =
        DrivePlanner(example_lra(), {.reverse = true, .uncertainty = kPartToPart}).look_ahead_s();
    EXPECT_GT(read_beyond(kPartToPart), ahead - 0.005);
    EXPECT_LE(read_beyond(kPartToPart), ahead + 0.005 + 1e-9);
    // Braked (a calibration's margins): the one step after.
    EXPECT_LE(read_beyond({0.01, 0.15}), 0.005 + 1e-9);
}

TEST(ActuatorDrives, ADecrescendoThroughTheStagesRingsNoLongerThanWithoutCompensation) {
    // The rest of the note reaches the planner: bench/feel's touch-click (50 ms from strong at
    // 235 Hz) on a 166 Hz Q-21 LRA, declared 175 Hz Q 15 with the default margins.
    Declaration truth = example_lra();
    truth.resonance_hz = 166.25;
    truth.q = 21.0;
    const auto stop = [&](bool compensation) {
        CueAdaptation adaptation = declared(example_lra(), true);
        adaptation.actuator->compensation = compensation;
        const auto strength =
            bench::Plant(truth).respond(adapt_cues(decrescendo(0.05, 235.0), 0.05, adaptation),
                                        kPlantRate, static_cast<std::size_t>(0.4 * kPlantRate));
        for (auto k = static_cast<std::size_t>(0.05 * kPlantRate); k < strength.size(); ++k) {
            if (strength[k] < 0.1) {
                return static_cast<double>(k) / kPlantRate - 0.05;
            }
        }
        return static_cast<double>(INFINITY);
    };
    EXPECT_LE(stop(true), stop(false));
}

}  // namespace
}  // namespace vibscore::render
