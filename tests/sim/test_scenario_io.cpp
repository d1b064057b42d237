// Scenario loading, validation, overrides and recording (sim/include/swa/sim/scenario_io.h).

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "scratch.h"
#include "swa/agent/config_io.h"
#include "swa/sim/scenario.h"
#include "swa/sim/scenario_io.h"

namespace swa::sim {
namespace {

using agent::ConfigError;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

ConfigError expectConfigError(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error;
  }
  ADD_FAILURE() << "expected a ConfigError";
  return ConfigError("<none>", {});
}

// The one problem that mentions `part` (fails if none or several do).
std::string problemAbout(const ConfigError& error, const std::string& part) {
  std::string found;
  int count = 0;
  for (const std::string& problem : error.problems()) {
    if (contains(problem, part)) {
      found = problem;
      ++count;
    }
  }
  EXPECT_EQ(count, 1) << "problems mentioning '" << part << "':\n" << error.what();
  return found;
}

std::string scenarioDir() {
  return (std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "deploy" / "scenarios").string();
}

using testing::ScratchFile;

std::string yamlOf(const Scenario& s) { return scenarioToYaml(s); }

// Valid, and different from the defaults in every field; awkward binary fractions test exact round trips.
Scenario everyFieldChanged() {
  Scenario s;
  s.uav_count = 12;
  s.seed = 18446744073709551615ULL;
  s.duration_s = 300.5;
  s.formation.spacing_m = 1.0 / 3.0 + 12.0;
  s.formation.position_jitter_m = 0.1 + 0.2;
  s.dynamics.rate_hz = 200.0;
  s.dynamics.velocity_lag_s = 0.7;
  s.dynamics.speed_limit_mps = 4.25;
  s.dynamics.failsafe_timeout_s = 0.3;
  s.dynamics.heading = HeadingMode::kZero;
  s.dynamics.heading_rate_std_radps = 0.01;
  s.wind.gust_std = 0.35;
  s.wind.gust_corr_s = 7.5;
  s.wind.common_std = 0.05;
  s.wind.common_corr_s = 30.0;
  s.imu.rate_hz = 50.0;
  s.imu.bias_std = 0.15;
  s.imu.noise_std = 1.2;
  s.imu.heading_noise_std_rad = 2e-7;
  s.mps.rate_hz = 20.0;
  s.mps.range_m = 55.0;
  s.mps.fov_deg = 120.0;
  s.mps.noise_model = MpsNoiseModel::kRangeBearing;
  // mps.noise_var_m2 stays: the range_bearing model below ignores it, and its dump is a comment (read as default)
  s.mps.range_std_m = 0.3;
  s.mps.bearing_std_rad = 0.02;
  s.mps.miss_probability = 0.1;
  s.mps.clutter_rate = 0.4;
  s.mps.ids = false;
  s.mps.latency_s = 0.05;
  s.gnss.rate_hz = 5.0;
  s.gnss.std_m = 0.7;
  s.gnss.dropout_start_s = 0.0;
  s.gnss.dropout_end_s = 95.5;
  s.gnss.keep_uavs = {0, 11};
  s.gnss.windows = {{3, 20.0, 40.0}, {11, 0.1 + 0.2, std::numeric_limits<double>::infinity()}, {3, 35.5, 1e5}};
  s.clock.mode = ClockMode::kRealtime;
  s.clock.speed = 2.5;
  s.agent.mode = agent::Mode::kAnchored;
  s.agent.formation.neighbourhood = agent::NeighbourhoodRule::kKNearest;  // so k is used
  s.agent.formation.k = 2;
  s.agent.formation.circle_fit = agent::CircleFit::kAlgebraic;
  s.agent.formation.radius_m = 11.0;  // deliberately not the spacing
  s.agent.focal.q_scale = 0.3;
  s.agent.surroundings.tentative_timeout_s = 0.4;
  return s;
}

// ------------------------------------------------------------------------------------------------------------

TEST(ScenarioDefaults, GivenADefaultScenario_ThenItHoldsDesignSection4AndThePaperDropout) {
  // GIVEN a default-constructed scenario
  const Scenario s;
  // THEN it is DESIGN §4 and the paper's GNSS-loss experiment
  EXPECT_EQ(s.uav_count, 8);
  EXPECT_EQ(s.seed, 1u);
  EXPECT_EQ(s.duration_s, 120.0);
  EXPECT_EQ(s.dynamics.rate_hz, 100.0);
  EXPECT_EQ(s.dynamics.velocity_lag_s, 1.0);
  EXPECT_EQ(s.wind.gust_std, 0.2);
  EXPECT_EQ(s.wind.gust_corr_s, 5.0);
  EXPECT_EQ(s.imu.rate_hz, 100.0);
  EXPECT_EQ(s.imu.bias_std, 0.05);
  EXPECT_EQ(s.mps.rate_hz, 10.0);
  EXPECT_EQ(s.mps.range_m, 40.0);
  EXPECT_EQ(s.mps.miss_probability, 0.05);
  EXPECT_TRUE(s.mps.ids);
  EXPECT_EQ(s.gnss.rate_hz, 10.0);
  EXPECT_EQ(s.gnss.dropout_start_s, 10.0);
  EXPECT_TRUE(std::isinf(s.gnss.dropout_end_s));
  EXPECT_TRUE(s.gnss.keep_uavs.empty());
  EXPECT_TRUE(s.gnss.windows.empty());
  EXPECT_EQ(s.clock.mode, ClockMode::kLockstep);
  // AND an empty (or comment-only, or empty-section) text parses to exactly these defaults
  EXPECT_EQ(yamlOf(parseScenario("", "<empty>")), yamlOf(s));
  EXPECT_EQ(yamlOf(parseScenario("# nothing\n\nwind:\nagent:\n", "<comments>")), yamlOf(s));
  // AND the default agent radius equals the default spacing, so "radius follows spacing" changes nothing
  EXPECT_EQ(s.agent.formation.radius_m, s.formation.spacing_m);
}

TEST(ScenarioFiles, GivenEachShippedScenario_WhenLoaded_ThenItHasTheIntendedValues) {
  const std::string dir = scenarioDir();
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;

  // dropout_4: the paper's dropout with 4 UAVs
  const Scenario d4 = loadScenario(dir + "/dropout_4.yaml");
  EXPECT_EQ(d4.uav_count, 4);
  EXPECT_EQ(d4.duration_s, 120.0);
  EXPECT_EQ(d4.gnss.dropout_start_s, 10.0);
  EXPECT_TRUE(std::isinf(d4.gnss.dropout_end_s));
  EXPECT_TRUE(d4.gnss.keep_uavs.empty());
  EXPECT_EQ(d4.agent.mode, agent::Mode::kSwa);
  EXPECT_EQ(d4.agent.formation.radius_m, 10.0);

  // dropout_8: the default scenario, every key spelled out
  const Scenario d8 = loadScenario(dir + "/dropout_8.yaml");
  EXPECT_EQ(d8.uav_count, 8);
  EXPECT_EQ(yamlOf(d8), yamlOf(Scenario{}));

  // swarm_16
  const Scenario s16 = loadScenario(dir + "/swarm_16.yaml");
  EXPECT_EQ(s16.uav_count, 16);
  EXPECT_EQ(s16.gnss.dropout_start_s, 10.0);
  EXPECT_EQ(s16.agent.mode, agent::Mode::kSwa);

  // anonymous_8: no IDs, clutter = 5 % of 8 detections
  const Scenario an = loadScenario(dir + "/anonymous_8.yaml");
  EXPECT_EQ(an.uav_count, 8);
  EXPECT_FALSE(an.mps.ids);
  EXPECT_EQ(an.mps.clutter_rate, 0.4);
  EXPECT_EQ(an.agent.mode, agent::Mode::kSwa);

  // anchored_8: UAV 0 keeps GNSS, agents in anchored mode
  const Scenario anc = loadScenario(dir + "/anchored_8.yaml");
  EXPECT_EQ(anc.uav_count, 8);
  EXPECT_EQ(anc.agent.mode, agent::Mode::kAnchored);
  EXPECT_EQ(anc.gnss.keep_uavs, std::vector<int>{0});

  // study_drift_vs_n: the shipped example study's base scenario (its study: section is swa_batch's; the study
  // itself is checked in tests/study/)
  const Scenario dvn = loadScenario(dir + "/study_drift_vs_n.yaml");
  EXPECT_EQ(dvn.uav_count, 8);
  EXPECT_EQ(dvn.gnss.dropout_start_s, 0.0);
  EXPECT_TRUE(std::isinf(dvn.gnss.dropout_end_s));
  EXPECT_EQ(dvn.agent.formation.k, 2);

  // study_wind: issue #44's study; its base is 8 UAVs in a 5 m/s westerly reading the accelerometer, for 600 s
  const Scenario wind = loadScenario(dir + "/study_wind.yaml");
  EXPECT_EQ(wind.uav_count, 8);
  EXPECT_EQ(wind.duration_s, 600.0);
  EXPECT_EQ(wind.wind.mean_mps, 5.0);
  EXPECT_EQ(wind.wind.direction_deg, 270.0);
  EXPECT_EQ(wind.imu.source, agent::ImuSource::kAccelerometer);
  EXPECT_EQ(wind.agent.focal.imu_source, agent::ImuSource::kAccelerometer);

  // return_home_8: issue #45's mission, written at the top of the scenario and held by every agent: cruising east
  // from 0 s, GNSS lost at 10 s, 500 m back west at 4 m/s, then a hold
  const Scenario home = loadScenario(dir + "/return_home_8.yaml");
  EXPECT_EQ(home.uav_count, 8);
  EXPECT_EQ(home.agent.mission.start, agent::MissionStart::kTime);
  ASSERT_EQ(home.agent.mission.legs.size(), 2u);
  EXPECT_EQ(home.agent.mission.legs[0].velocity_mps, agent::Vec2(3, 0));
  EXPECT_EQ(home.agent.mission.legs[0].duration_s, 10.0);
  EXPECT_EQ(home.agent.mission.legs[1].velocity_mps, agent::Vec2(-4, 0));
  EXPECT_EQ(home.agent.mission.legs[1].duration_s, 125.0);
  EXPECT_EQ(sim::missionStart(home), 0.0);

  // AND there are exactly these eight, and each one round-trips through its dump
  int count = 0;
  for (const auto& file : std::filesystem::directory_iterator(dir)) {
    if (file.path().extension() != ".yaml") continue;
    ++count;
    const Scenario loaded = loadScenario(file.path().string());
    EXPECT_EQ(yamlOf(parseScenario(yamlOf(loaded), "dump")), yamlOf(loaded)) << file.path();
  }
  EXPECT_EQ(count, 8);
}

TEST(ScenarioOverride, GivenASetOfEachRequiredKey_WhenApplied_ThenExactlyThatFieldChanges) {
  struct Case {
    std::string set;
    std::function<void(Scenario&)> expect;
  };
  const std::vector<Case> cases = {
      {"uav_count=16", [](Scenario& s) { s.uav_count = 16; }},
      {"seed=18446744073709551615", [](Scenario& s) { s.seed = std::numeric_limits<std::uint64_t>::max(); }},
      {"duration_s=600", [](Scenario& s) { s.duration_s = 600.0; }},
      // the agents' desired spacing follows the formation spacing (it was not given explicitly)
      {"formation.spacing_m=12.5",
       [](Scenario& s) {
         s.formation.spacing_m = 12.5;
         s.agent.formation.radius_m = 12.5;
       }},
      {"agent.mode=standalone", [](Scenario& s) { s.agent.mode = agent::Mode::kStandalone; }},
      {"agent.formation.neighbourhood=k_nearest",
       [](Scenario& s) { s.agent.formation.neighbourhood = agent::NeighbourhoodRule::kKNearest; }},
      {"agent.circle_fit=algebraic", [](Scenario& s) { s.agent.formation.circle_fit = agent::CircleFit::kAlgebraic; }},
      {"imu.bias_std=0.15", [](Scenario& s) { s.imu.bias_std = 0.15; }},
      {"mps.ids=false", [](Scenario& s) { s.mps.ids = false; }},
      {"mps.miss_probability=0.2", [](Scenario& s) { s.mps.miss_probability = 0.2; }},
      {"gnss.dropout_start_s=0", [](Scenario& s) { s.gnss.dropout_start_s = 0.0; }},
      {"wind.gust_std=0.5", [](Scenario& s) { s.wind.gust_std = 0.5; }},
      {"gnss.windows=[{uav: 3, start_s: 20, end_s: 40}, {uav: 5, start_s: 0}]",
       [](Scenario& s) {
         s.gnss.windows = {{3, 20.0, 40.0}, {5, 0.0, std::numeric_limits<double>::infinity()}};
       }},
  };
  for (const Case& c : cases) {
    // GIVEN the default scenario file and one --set
    // WHEN it is loaded with the override
    const Scenario loaded = loadScenario(scenarioDir() + "/dropout_8.yaml", {c.set});
    // THEN the result is the defaults with exactly that field changed (the dump holds every field)
    Scenario expected;
    c.expect(expected);
    EXPECT_EQ(yamlOf(loaded), yamlOf(expected)) << "--set " << c.set;
    EXPECT_NE(yamlOf(loaded), yamlOf(Scenario{})) << "--set " << c.set;
  }
}

TEST(ScenarioOverride, GivenSeveralSets_ThenTheyApplyInOrderAndOverrideTheFile) {
  // GIVEN a file, and overrides that only together satisfy a rule, plus a repeated key
  const Scenario s = parseScenario("uav_count: 4\ngnss: {keep_uavs: [3]}\n", "<text>",
                                   {"dynamics.rate_hz=200", "imu.rate_hz=200", "uav_count=6", "uav_count=5",
                                    "gnss.keep_uavs=[0, 4]", "gnss.dropout_end_s=60", "agent.focal.q_scale=0.5"});
  // THEN the last value of each key wins and relations are checked on the final values
  EXPECT_EQ(s.uav_count, 5);
  EXPECT_EQ(s.dynamics.rate_hz, 200.0);
  EXPECT_EQ(s.imu.rate_hz, 200.0);
  EXPECT_EQ(s.gnss.keep_uavs, (std::vector<int>{0, 4}));
  EXPECT_EQ(s.gnss.dropout_end_s, 60.0);
  EXPECT_EQ(s.agent.focal.q_scale, 0.5);
}

TEST(ScenarioParse, GivenAFileWithManyDistinctProblems_WhenLoaded_ThenOneErrorListsThemAll) {
  // GIVEN a file with an unknown key, a wrong type, an out-of-range value, a non-finite value, a bad enum, a bad
  // agent value, an unknown agent key, a keep_uavs index outside the swarm and a sensor rate that does not divide
  const ScratchFile file(
      "uav_count: 4\n"
      "duraton_s: 60\n"
      "formation:\n"
      "  spacing_m: ten\n"
      "mps:\n"
      "  miss_probability: 1.0\n"
      "  noise_model: lidar\n"
      "imu:\n"
      "  rate_hz: 30\n"
      "wind:\n"
      "  gust_std: .nan\n"
      "gnss:\n"
      "  keep_uavs: [0, 7]\n"
      "agent:\n"
      "  k: 0\n"
      "  focal:\n"
      "    q_scal: 2\n");
  // WHEN it is loaded, with two bad overrides as well
  const ConfigError error = expectConfigError([&] { loadScenario(file.path(), {"clock.mode=fast", "seed"}); });
  // THEN one error lists every problem, each naming its key (and, for the file, where it is)
  EXPECT_EQ(error.source(), file.path());
  EXPECT_EQ(error.problems().size(), 11u) << error.what();
  EXPECT_EQ(problemAbout(error, "duraton_s"),
            "unknown key 'duraton_s' (did you mean 'duration_s'?) (line 2, column 1)");
  EXPECT_TRUE(contains(problemAbout(error, "formation.spacing_m"), "'ten' is not a number; expected a number in m"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.spacing_m"), "(line 4, column 14)"));
  EXPECT_EQ(problemAbout(error, "miss_probability"),
            "mps.miss_probability = 1.0 is out of range [0, 1) (line 6, column 21)");
  EXPECT_TRUE(contains(problemAbout(error, "noise_model"), "expected one of: isotropic, range_bearing"));
  EXPECT_TRUE(contains(problemAbout(error, "imu.rate_hz"), "must divide dynamics.rate_hz = 100 Hz exactly"));
  EXPECT_TRUE(contains(problemAbout(error, "gust_std"), "wind.gust_std = .nan is not a finite number"));
  EXPECT_TRUE(contains(problemAbout(error, "keep_uavs"), "lists UAV 7, but the UAV indices are 0..3"));
  EXPECT_EQ(problemAbout(error, "agent.k"), "agent.k = 0 is out of range [1, 16] (line 15, column 6)");
  EXPECT_TRUE(contains(problemAbout(error, "q_scal"), "did you mean 'agent.focal.q_scale'?"));
  EXPECT_TRUE(contains(problemAbout(error, "clock.mode"), "'fast' is not valid; expected one of: lockstep, realtime"));
  EXPECT_TRUE(contains(problemAbout(error, "clock.mode"), "(from --set clock.mode=fast)"));
  EXPECT_TRUE(contains(problemAbout(error, "'seed'"), "malformed override 'seed'; expected key=value"));
  // AND what() prefixes every line with the file
  EXPECT_EQ(std::string(error.what()).rfind(file.path() + ": ", 0), 0u);
}

TEST(ScenarioParse, GivenValuesOfTheWrongShapeOrType_ThenEachIsReported) {
  const ConfigError error = expectConfigError([] {
    parseScenario(
        "uav_count: 2.5\n"
        "seed: -1\n"
        "duration_s: \"60\"\n"
        "mps: {ids: yes, fov_deg: 0}\n"
        "gnss: {keep_uavs: 0, dropout_start_s: .inf}\n"
        "clock: 3\n"
        "agent: {mode: [swa]}\n",
        "<text>");
  });
  EXPECT_EQ(error.problems().size(), 9u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "uav_count ="), "uav_count = 2.5 is not an integer"));
  EXPECT_TRUE(contains(problemAbout(error, "seed"), "seed = -1 is out of range [0, 18446744073709551615]"));
  EXPECT_TRUE(contains(problemAbout(error, "duration_s"), "is a string"));
  EXPECT_TRUE(contains(problemAbout(error, "mps.ids"), "expected true or false"));
  EXPECT_TRUE(contains(problemAbout(error, "fov_deg"), "mps.fov_deg = 0 is out of range (0, 360] deg"));
  EXPECT_TRUE(contains(problemAbout(error, "keep_uavs"), "must be a list of UAV indices"));
  EXPECT_TRUE(contains(problemAbout(error, "dropout_start_s"), "is not a finite number"));
  EXPECT_TRUE(contains(problemAbout(error, "'clock'"), "must be a map of parameters, got a scalar"));
  EXPECT_TRUE(contains(problemAbout(error, "agent.mode"), "got a sequence"));
}

TEST(ScenarioParse, GivenDropoutEnd_ThenOnlyItAcceptsInfinityAndItMustFollowTheStart) {
  // .inf or left out: never restored
  EXPECT_TRUE(std::isinf(parseScenario("gnss: {dropout_end_s: .inf}\n", "<t>").gnss.dropout_end_s));
  EXPECT_TRUE(std::isinf(parseScenario("gnss: {dropout_start_s: 5}\n", "<t>").gnss.dropout_end_s));
  EXPECT_EQ(parseScenario("gnss: {dropout_end_s: 30}\n", "<t>").gnss.dropout_end_s, 30.0);
  // no other key takes infinity, and -inf is not "never"
  const ConfigError error =
      expectConfigError([] { parseScenario("duration_s: .inf\ngnss: {dropout_end_s: -.inf}\n", "<t>"); });
  EXPECT_EQ(error.problems().size(), 2u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "duration_s"), "is not a finite number"));
  EXPECT_TRUE(contains(problemAbout(error, "dropout_end_s"), "or .inf"));
  // an empty outage window is a mistake
  const ConfigError window =
      expectConfigError([] { parseScenario("gnss: {dropout_start_s: 20, dropout_end_s: 20}\n", "<t>"); });
  ASSERT_EQ(window.problems().size(), 1u) << window.what();
  EXPECT_TRUE(contains(window.problems()[0], "gnss.dropout_end_s = 20 s must be > gnss.dropout_start_s = 20 s"));
}

TEST(ScenarioParse, GivenAShortcutAndItsLongForm_ThenItIsAConflict) {
  // GIVEN a file that sets the neighbour count twice, once by the shortcut, and the fit twice too
  const ConfigError error = expectConfigError([] {
    parseScenario(
        "agent:\n"
        "  k: 2\n"
        "  formation:\n"
        "    k: 4\n"
        "    circle_fit: algebraic\n"
        "  circle_fit: fixed_radius\n",
        "<text>");
  });
  // THEN each pair is one problem naming both spellings
  ASSERT_EQ(error.problems().size(), 2u) << error.what();
  EXPECT_EQ(problemAbout(error, "formation.k'"),
            "'agent.formation.k' and 'agent.k' set the same parameter ('agent.k' is a shortcut for "
            "'agent.formation.k'); give only one (line 4, column 5)");
  EXPECT_TRUE(contains(problemAbout(error, "circle_fit"), "'agent.circle_fit' and 'agent.formation.circle_fit'"));

  // AND either form alone is fine, and a --set of either form replaces the file's value without a conflict
  const std::string knn = "agent: {formation: {neighbourhood: k_nearest}}\n";  // the rule k applies to
  EXPECT_EQ(parseScenario("agent: {k: 2, formation: {neighbourhood: k_nearest}}\n", "<t>").agent.formation.k, 2);
  EXPECT_EQ(parseScenario("agent: {formation: {k: 2, neighbourhood: k_nearest}}\n", "<t>").agent.formation.k, 2);
  EXPECT_EQ(
      parseScenario("agent: {formation: {k: 2, neighbourhood: k_nearest}}\n", "<t>", {"agent.k=4"}).agent.formation.k,
      4);
  EXPECT_EQ(parseScenario(knn, "<t>", {"agent.k=2", "agent.formation.k=5"}).agent.formation.k, 5);
  EXPECT_EQ(parseScenario("agent: {circle_fit: algebraic}\n", "<t>").agent.formation.circle_fit,
            agent::CircleFit::kAlgebraic);
}

TEST(ScenarioParse, GivenWindOrAccelerometerKeysThatChangeNothing_ThenEachIsAnErrorThatSaysWhy) {
  // GIVEN a wind direction and turn rate without a mean wind, and the accelerometer's errors for tilt-reading agents
  const ConfigError error = expectConfigError([] {
    parseScenario(
        "wind: {direction_deg: 90, turn_rate_dps: 0.1}\n"
        "imu: {source: tilt, attitude_error_std_rad: 0.01, accel_bias_std_mps2: 0.2, "
        "accel_noise_std_mps2: 0.5}\n",
        "<t>");
  });
  // THEN one error names all five, each with what turns it off
  ASSERT_EQ(error.problems().size(), 5u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "wind.direction_deg"), "applies to a mean wind only (wind.mean_mps is 0)"));
  EXPECT_TRUE(contains(problemAbout(error, "wind.turn_rate_dps"), "a mean wind only"));
  EXPECT_TRUE(contains(problemAbout(error, "imu.attitude_error_std_rad"),
                       "applies to the accelerometer source only (imu.source is tilt)"));
  EXPECT_TRUE(contains(problemAbout(error, "imu.accel_bias_std_mps2"), "the accelerometer source only"));
  EXPECT_TRUE(contains(problemAbout(error, "imu.accel_noise_std_mps2"), "the accelerometer source only"));
  // AND with a mean wind and the accelerometer each is taken, and the agents read what the simulator publishes
  const Scenario ok = parseScenario(
      "wind: {mean_mps: 5, direction_deg: 90, turn_rate_dps: 0.1}\ndynamics: {drag_per_s: 0.3}\n"
      "imu: {source: accelerometer, attitude_error_std_rad: 0.01, accel_bias_std_mps2: 0.2}\n",
      "<t>");
  EXPECT_EQ(ok.wind.mean_mps, 5.0);
  EXPECT_EQ(ok.wind.direction_deg, 90.0);
  EXPECT_EQ(ok.wind.turn_rate_dps, 0.1);
  EXPECT_EQ(ok.dynamics.drag_per_s, 0.3);
  EXPECT_EQ(ok.imu.attitude_error_std_rad, 0.01);
  EXPECT_EQ(ok.agent.focal.imu_source, agent::ImuSource::kAccelerometer);
  EXPECT_EQ(parseScenario("imu: {source: tilt}\n", "<t>").agent.focal.imu_source, agent::ImuSource::kTilt);
  // AND the agents' own key wins over the simulator's when given
  EXPECT_EQ(
      parseScenario("imu: {source: tilt}\nagent: {focal: {imu_source: accelerometer}}\n", "<t>").agent.focal.imu_source,
      agent::ImuSource::kAccelerometer);
  // AND values out of their bounds are refused: a wind of 40 m/s, a negative drag, an unknown source
  EXPECT_EQ(expectConfigError([] {
              parseScenario("wind: {mean_mps: 40}\ndynamics: {drag_per_s: -0.1}\nimu: {source: gyro}\n", "<t>");
            })
                .problems()
                .size(),
            3u);
}

TEST(ScenarioParse, GivenKeysTheChosenModesIgnore_ThenEachIsAnErrorThatSaysWhich) {
  // GIVEN the realtime speed in lockstep, range/bearing noise with the isotropic model, the PX4 loss timeout with
  // the direct interface, and the agents' k with the gabriel rule
  const ConfigError error = expectConfigError([] {
    parseScenario(
        "clock: {mode: lockstep, speed: 2}\nmps: {range_std_m: 0.3, bearing_std_rad: 0.02}\n"
        "vehicle: {com_of_loss_t_s: 2}\n",
        "<t>", {"agent.k=2"});
  });
  // THEN one error names all five, each with the choice that turns it off
  ASSERT_EQ(error.problems().size(), 5u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "clock.speed"), "applies to realtime mode only (clock.mode is lockstep)"));
  EXPECT_TRUE(contains(problemAbout(error, "mps.range_std_m"), "the range_bearing noise model only"));
  EXPECT_TRUE(contains(problemAbout(error, "mps.bearing_std_rad"), "the range_bearing noise model only"));
  EXPECT_TRUE(contains(problemAbout(error, "vehicle.com_of_loss_t_s"), "the px4 vehicle interface only"));
  EXPECT_TRUE(contains(problemAbout(error, "agent.k "),
                       "agent.k applies to the k_nearest rule only (agent.formation.neighbourhood is gabriel)"));
  // AND each is accepted where its mode is chosen
  const Scenario ok = parseScenario(
      "clock: {mode: realtime, speed: 2}\nmps: {noise_model: range_bearing, range_std_m: 0.3}\n"
      "vehicle: {interface: px4, com_of_loss_t_s: 2}\nagent: {formation: {neighbourhood: k_nearest, k: 2}}\n",
      "<t>");
  EXPECT_EQ(ok.clock.speed, 2.0);
  EXPECT_EQ(ok.mps.range_std_m, 0.3);
  EXPECT_EQ(ok.agent.formation.k, 2);
  // AND a --set that turns a file's key off (lockstep for a realtime file, as a test or a study may) is accepted
  EXPECT_EQ(parseScenario("clock: {mode: realtime, speed: 2}\n", "<t>", {"clock.mode=lockstep"}).clock.mode,
            ClockMode::kLockstep);
  // AND a recording's scenario, written by a version whose dump gave every key, is read (swa_replay --check)
  const std::string old_dump =
      "clock: {mode: lockstep, speed: 1}\nagent: {formation: {neighbourhood: gabriel, k: 3}}\n";
  EXPECT_EQ(expectConfigError([&] { parseScenario(old_dump, "<t>"); }).problems().size(), 2u);
  EXPECT_EQ(parseRecordedScenario(old_dump, "<t>").clock.speed, 1.0);
}

TEST(ScenarioParse, GivenSensorRates_ThenEachMustDivideTheDynamicsRate) {
  // GIVEN rates that divide 100 Hz (every step, every 2nd, every 50th) THEN they are accepted
  const Scenario ok = parseScenario("imu: {rate_hz: 50}\nmps: {rate_hz: 2}\ngnss: {rate_hz: 0.5}\n", "<t>");
  EXPECT_EQ(ok.imu.rate_hz, 50.0);
  EXPECT_EQ(ok.gnss.rate_hz, 0.5);
  // GIVEN three that do not (not a whole number of steps, or faster than the simulation)
  const ConfigError error =
      expectConfigError([] { parseScenario("imu: {rate_hz: 30}\nmps: {rate_hz: 7}\ngnss: {rate_hz: 200}\n", "<t>"); });
  // THEN each is reported with the arithmetic
  ASSERT_EQ(error.problems().size(), 3u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "imu.rate_hz"), "100 / 30 = 3.333 is not a whole number"));
  EXPECT_TRUE(contains(problemAbout(error, "mps.rate_hz"), "must divide dynamics.rate_hz = 100 Hz exactly"));
  EXPECT_TRUE(contains(problemAbout(error, "gnss.rate_hz"), "100 / 200 = 0.5"));
  // AND changing the simulation rate re-judges them
  EXPECT_NO_THROW(
      parseScenario("dynamics: {rate_hz: 120}\nimu: {rate_hz: 30}\nmps: {rate_hz: 10}\n"
                    "gnss: {rate_hz: 10}\n",
                    "<t>"));
  const ConfigError changed = expectConfigError([] { parseScenario("", "<t>", {"dynamics.rate_hz=150"}); });
  ASSERT_EQ(changed.problems().size(), 1u) << changed.what();  // imu 100 Hz; mps and gnss 10 Hz divide 150 Hz
  EXPECT_TRUE(contains(changed.problems()[0], "imu.rate_hz = 100 Hz must divide dynamics.rate_hz = 150 Hz"));
}

TEST(ScenarioParse, GivenNoAgentSensor_ThenTheAgentKnowsTheSimulatedFieldOfViewAndMounting) {
  // GIVEN only the simulator's sensor THEN the agents are told its field of view and mounting
  const Scenario s = parseScenario("", "<t>", {"mps.fov_deg=240", "mps.mount_deg=30"});
  EXPECT_EQ(s.agent.sensor.fov_deg, 240.0);
  EXPECT_EQ(s.agent.sensor.mount_deg, 30.0);
  EXPECT_EQ(parseScenario("", "<t>").agent.sensor.fov_deg, 360.0);
  // GIVEN the agent's own (a wrong belief, for a study) THEN it wins
  EXPECT_EQ(parseScenario("", "<t>", {"mps.fov_deg=240", "agent.sensor.fov_deg=360"}).agent.sensor.fov_deg, 360.0);
}

TEST(ScenarioParse, GivenNoExplicitRadius_ThenTheAgentRadiusFollowsTheSpacing) {
  // GIVEN a spacing and no agent radius THEN the agents aim for the spacing
  EXPECT_EQ(parseScenario("formation: {spacing_m: 15}\n", "<t>").agent.formation.radius_m, 15.0);
  EXPECT_EQ(parseScenario("", "<t>", {"formation.spacing_m=7.5"}).agent.formation.radius_m, 7.5);
  // GIVEN an explicit radius (file or --set) THEN it wins over the spacing
  const Scenario given = parseScenario("formation: {spacing_m: 15}\nagent: {formation: {radius_m: 12}}\n", "<t>");
  EXPECT_EQ(given.formation.spacing_m, 15.0);
  EXPECT_EQ(given.agent.formation.radius_m, 12.0);
  EXPECT_EQ(
      parseScenario("formation: {spacing_m: 15}\n", "<t>", {"agent.formation.radius_m=9"}).agent.formation.radius_m,
      9.0);
  // AND a derived radius that breaks the agent's own rule says where it came from
  const ConfigError error = expectConfigError(
      [] { parseScenario("formation: {spacing_m: 30}\nagent: {formation: {sensing_range_m: 25}}\n", "<t>"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0],
                       "agent.formation.radius_m (= formation.spacing_m) = 30 must be < "
                       "agent.formation.sensing_range_m = 25"))
      << error.what();
}

TEST(ScenarioParse, GivenKeepUavs_ThenIndicesMustBeInsideTheSwarmAndDistinct) {
  EXPECT_EQ(parseScenario("uav_count: 3\ngnss: {keep_uavs: [2, 0]}\n", "<t>").gnss.keep_uavs, (std::vector<int>{2, 0}));
  const ConfigError error =
      expectConfigError([] { parseScenario("uav_count: 3\ngnss: {keep_uavs: [1, 1, 3, x]}\n", "<t>"); });
  EXPECT_EQ(error.problems().size(), 1u) << error.what();  // the element that is not a number blocks the list
  EXPECT_TRUE(contains(problemAbout(error, "keep_uavs[3]"), "'x' is not a number"));
  const ConfigError range =
      expectConfigError([] { parseScenario("uav_count: 3\ngnss: {keep_uavs: [1, 1, 3]}\n", "<t>"); });
  EXPECT_EQ(range.problems().size(), 2u) << range.what();
  EXPECT_TRUE(contains(problemAbout(range, "more than once"), "UAV 1"));
  EXPECT_TRUE(contains(problemAbout(range, "lists UAV 3"), "(uav_count = 3)"));
}

TEST(ScenarioGnssWindows, GivenPerUavWindowsInTheFileOrASet_WhenLoaded_ThenEachIsKeptAsWritten) {
  const double inf = std::numeric_limits<double>::infinity();
  // GIVEN windows in block and flow style, one without end_s, one with an explicit .inf, two overlapping ones
  const Scenario s = parseScenario(
      "uav_count: 6\n"
      "gnss:\n"
      "  windows:\n"
      "    - {uav: 3, start_s: 20, end_s: 40}\n"
      "    - uav: 5\n"
      "      start_s: 0\n"
      "    - {uav: 3, start_s: 30.5, end_s: .inf}\n",
      "<t>");
  // THEN they are read in order, a missing end_s meaning never restored
  ASSERT_EQ(s.gnss.windows.size(), 3u);
  EXPECT_EQ(s.gnss.windows[0].uav, 3);
  EXPECT_EQ(s.gnss.windows[0].start_s, 20.0);
  EXPECT_EQ(s.gnss.windows[0].end_s, 40.0);
  EXPECT_EQ(s.gnss.windows[1].uav, 5);
  EXPECT_EQ(s.gnss.windows[1].start_s, 0.0);
  EXPECT_EQ(s.gnss.windows[1].end_s, inf);
  EXPECT_EQ(s.gnss.windows[2].start_s, 30.5);
  EXPECT_EQ(s.gnss.windows[2].end_s, inf);
  // AND the common window is untouched
  EXPECT_EQ(s.gnss.dropout_start_s, 10.0);

  // WHEN a --set gives the list THEN it replaces the file's whole list; [] clears it
  const std::string file = "uav_count: 6\ngnss: {windows: [{uav: 1, start_s: 2}, {uav: 2, start_s: 3}]}\n";
  const Scenario replaced = parseScenario(file, "<t>", {"gnss.windows=[{uav: 4, start_s: 1.5, end_s: 2.5}]"});
  ASSERT_EQ(replaced.gnss.windows.size(), 1u);
  EXPECT_EQ(replaced.gnss.windows[0].uav, 4);
  EXPECT_EQ(replaced.gnss.windows[0].start_s, 1.5);
  EXPECT_EQ(replaced.gnss.windows[0].end_s, 2.5);
  EXPECT_TRUE(parseScenario(file, "<t>", {"gnss.windows=[]"}).gnss.windows.empty());
  // AND the UAV check uses the final uav_count (a --set may grow the swarm to fit the windows)
  EXPECT_EQ(parseScenario("uav_count: 2\ngnss: {windows: [{uav: 7, start_s: 1}]}\n", "<t>", {"uav_count=8"})
                .gnss.windows.size(),
            1u);
}

TEST(ScenarioGnssWindows, GivenManyBrokenWindows_WhenLoaded_ThenOneErrorListsEveryProblem) {
  // GIVEN a file whose window entries are wrong in many ways
  const ScratchFile file(
      "uav_count: 4\n"
      "gnss:\n"
      "  windows:\n"
      "    - {uav: 1, start_s: -1}\n"
      "    - {uav: 2, start_s: 30, end_s: 30}\n"
      "    - {uav: 0, start: 5}\n"
      "    - {uav: \"2\", start_s: .inf}\n"
      "    - 3\n"
      "    - {start_s: 1, end_s: [2]}\n"
      "    - {uav: 1, start_s: 2, uav: 3}\n"
      "    - {uav: 1.5, start_s: 2, end_s: 1}\n");
  // WHEN it is loaded
  const ConfigError error = expectConfigError([&] { loadScenario(file.path()); });
  // THEN one error lists every problem, each naming the entry and where it is
  EXPECT_EQ(error.problems().size(), 12u) << error.what();
  EXPECT_EQ(problemAbout(error, "windows[0]"),
            "gnss.windows[0].start_s = -1 is out of range [0, 1e+06] s (line 4, column 25)");
  EXPECT_EQ(problemAbout(error, "windows[1]"),
            "gnss.windows[1].end_s = 30 s must be > gnss.windows[1].start_s = 30 s: the outage would be empty "
            "(leave end_s out for one that never ends) (line 5, column 36)");
  EXPECT_TRUE(
      contains(problemAbout(error, "'start'"), "unknown key 'start' in gnss.windows[2] (did you mean 'start_s'?)"));
  EXPECT_TRUE(contains(problemAbout(error, "gnss.windows[2] has no start_s"), "(line 6, column 7)"));
  EXPECT_TRUE(contains(problemAbout(error, "windows[3].uav"), "gnss.windows[3].uav = \"2\" is a string"));
  EXPECT_TRUE(contains(problemAbout(error, "windows[3].start_s"), "= .inf is not a finite number"));
  EXPECT_TRUE(contains(problemAbout(error, "windows[4]"),
                       "gnss.windows[4] must be a map such as {uav: 3, "
                       "start_s: 20, end_s: 40}, got a scalar (line 8, column 7)"));
  EXPECT_TRUE(contains(problemAbout(error, "gnss.windows[5] has no uav"), "expected a map such as"));
  EXPECT_TRUE(contains(problemAbout(error, "windows[5].end_s"),
                       "must be a number in s within (0, 1e+06] or "
                       ".inf, got a sequence"));
  EXPECT_TRUE(contains(problemAbout(error, "duplicate"), "duplicate key 'gnss.windows[6].uav'"));
  EXPECT_TRUE(contains(problemAbout(error, "windows[7].uav"), "gnss.windows[7].uav = 1.5 is not an integer"));
  EXPECT_TRUE(contains(problemAbout(error, "windows[7].end_s"), "end_s = 1 s must be > gnss.windows[7].start_s = 2 s"));
}

TEST(ScenarioGnssWindows, GivenWindowsForUavsOutsideTheSwarmOrOfTheWrongShape_ThenEachIsReported) {
  // GIVEN well-formed windows, two of them for UAVs the swarm does not have
  const ConfigError outside = expectConfigError([] {
    parseScenario("uav_count: 4\ngnss: {windows: [{uav: 4, start_s: 1}, {uav: 2, start_s: 1}, {uav: 7, start_s: 0}]}\n",
                  "<t>");
  });
  // THEN each is named against uav_count
  ASSERT_EQ(outside.problems().size(), 2u) << outside.what();
  EXPECT_EQ(problemAbout(outside, "windows[0]"),
            "gnss.windows[0].uav = 4 is not a UAV of the swarm: the UAV indices are 0..3 (uav_count = 4)");
  EXPECT_TRUE(contains(problemAbout(outside, "windows[2]"), "uav = 7 is not a UAV of the swarm"));

  // GIVEN a single window instead of a list THEN the shape is reported
  const ConfigError shape = expectConfigError([] { parseScenario("gnss: {windows: {uav: 1, start_s: 2}}\n", "<t>"); });
  ASSERT_EQ(shape.problems().size(), 1u) << shape.what();
  EXPECT_EQ(shape.problems()[0],
            "gnss.windows must be a list of outage windows such as [{uav: 3, start_s: 20, end_s: 40}] or [] (end_s "
            "optional: .inf = never restored), got a map (line 1, column 17)");
  // GIVEN a --set whose window is wrong in two ways THEN both are reported, located at the --set
  const std::string set = "gnss.windows=[{uav: 1, start_s: x, stop_s: 3}]";
  const ConfigError bad_set = expectConfigError([&] { parseScenario("", "<t>", {set}); });
  ASSERT_EQ(bad_set.problems().size(), 2u) << bad_set.what();
  EXPECT_EQ(problemAbout(bad_set, "'x'"),
            "gnss.windows[0].start_s = 'x' is not a number; expected a number in s within [0, 1e+06] (from --set " +
                set + ")");
  EXPECT_TRUE(contains(problemAbout(bad_set, "unknown key"), "unknown key 'stop_s' in gnss.windows[0]"));
  // GIVEN a --set that is not YAML THEN that is the problem
  const ConfigError not_yaml = expectConfigError([] { parseScenario("", "<t>", {"gnss.windows=[{uav: 1"}); });
  ASSERT_EQ(not_yaml.problems().size(), 1u) << not_yaml.what();
  EXPECT_TRUE(contains(not_yaml.problems()[0], "gnss.windows = '[{uav: 1' is not a valid YAML value"));
}

TEST(ScenarioFiles, GivenTheCommentedWindowsExampleOfDropout8_WhenUncommented_ThenItLoads) {
  // GIVEN dropout_8.yaml with its commented gnss.windows example uncommented
  std::ifstream in(scenarioDir() + "/dropout_8.yaml");
  std::string text;
  bool found = false;
  for (std::string line; std::getline(in, line);) {
    if (line == "  # windows:") {
      line = "  windows:";
      found = true;
    } else if (line.rfind("  #   - ", 0) == 0) {
      line = "    - " + line.substr(8);
    }
    text += line + '\n';
  }
  ASSERT_TRUE(found);
  // WHEN it is parsed THEN it is the default scenario plus those windows
  const Scenario s = parseScenario(text, "dropout_8 with windows");
  ASSERT_EQ(s.gnss.windows.size(), 2u);
  EXPECT_EQ(s.gnss.windows[0].uav, 3);
  EXPECT_EQ(s.gnss.windows[1].uav, 5);
  EXPECT_TRUE(std::isinf(s.gnss.windows[1].end_s));
  Scenario without = s;
  without.gnss.windows.clear();
  EXPECT_EQ(yamlOf(without), yamlOf(Scenario{}));
}

TEST(ScenarioParse, GivenMisplacedKeys_ThenTheHintNamesTheRightPlace) {
  const ConfigError error = expectConfigError([] {
    parseScenario("mode: anchored\nimu: {gust_std: 1}\nagent: {formation: {raduis_m: 5}}\nwind.gust_std: 1\n", "<t>",
                  {"agent.formation=3", "agent.kk=2"});
  });
  EXPECT_EQ(error.problems().size(), 6u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "'mode'"), "did you mean 'agent.mode'?"));
  EXPECT_TRUE(contains(problemAbout(error, "imu.gust_std"), "did you mean 'wind.gust_std'?"));
  EXPECT_TRUE(contains(problemAbout(error, "raduis_m"), "did you mean 'agent.formation.radius_m'?"));
  EXPECT_TRUE(contains(problemAbout(error, "dotted key"), "must be written nested"));
  EXPECT_TRUE(contains(problemAbout(error, "group of parameters"), "'agent.formation'"));
  EXPECT_TRUE(contains(problemAbout(error, "agent.kk"), "did you mean 'agent.k'?"));
}

TEST(ScenarioLoad, GivenAMissingFileOrBrokenYaml_ThenTheErrorSaysSo) {
  // missing file: named, and bad overrides are still reported with it
  const std::string path = "/nonexistent/swa/scenario.yaml";
  const ConfigError missing = expectConfigError([&] { loadScenario(path, {"uav_count=0"}); });
  EXPECT_EQ(missing.source(), path);
  ASSERT_EQ(missing.problems().size(), 2u) << missing.what();
  EXPECT_EQ(missing.problems()[0], "scenario file does not exist");
  EXPECT_TRUE(contains(missing.problems()[1], "uav_count = 0 is out of range [1, 256] (from --set uav_count=0)"));
  // YAML syntax error: line and column
  const ConfigError syntax = expectConfigError([] { parseScenario("uav_count: 4\nwind: [1, 2\n", "bad.yaml"); });
  ASSERT_EQ(syntax.problems().size(), 1u) << syntax.what();
  EXPECT_TRUE(contains(syntax.problems()[0], "invalid YAML at line ")) << syntax.what();
  EXPECT_EQ(std::string(syntax.what()).rfind("bad.yaml: invalid YAML at line", 0), 0u);
  // an unclosed '[' or '{' is reported where YAML gave up, one or more lines late: the error also names where it was
  // opened, past brackets in quotes and comments (issue #30)
  const ConfigError flow = expectConfigError([] {
    parseScenario("uav_count: 4  # a comment with a [ bracket\nlabel: '[x'\nwind: [1, 2\nseed: 3\n", "bad.yaml");
  });
  EXPECT_TRUE(contains(flow.what(), "(the '[' at line 3, column 7 is never closed)")) << flow.what();
  // a top level that is not a map, and two documents
  EXPECT_TRUE(contains(expectConfigError([] { parseScenario("- 1\n", "<t>"); }).what(), "must be a map"));
  EXPECT_TRUE(
      contains(expectConfigError([] { parseScenario("a: 1\n---\nb: 2\n", "<t>"); }).what(), "2 YAML documents"));
}

TEST(ScenarioLoad, GivenADeviceOrAHugeFile_ThenAClearErrorAtOnce) {
  // Before issue #11: /dev/zero grew to 6 GB; a 10 MB scenario took 24 s, 3.3 GB and 5 million error lines.
  const ConfigError zero = expectConfigError([] { loadScenario("/dev/zero", {}); });
  ASSERT_EQ(zero.problems().size(), 1u) << zero.what();
  EXPECT_EQ(zero.problems()[0], "is a device, pipe or socket, not a scenario file");
  const std::string big = ::testing::TempDir() + "swa_big_scenario.yaml";
  {
    std::ofstream out(big);
    for (int i = 0; i < 400000; ++i) out << "uav_count: x" << i << "\n";  // ~7 MB of the same mistake
  }
  const ConfigError huge = expectConfigError([&] { loadScenario(big, {}); });
  ASSERT_EQ(huge.problems().size(), 1u) << huge.what();
  EXPECT_TRUE(contains(huge.problems()[0], "a scenario file may have at most 1048576 (1 MiB)")) << huge.what();
  std::remove(big.c_str());
  // under the size limit, 60000 repeated keys: refused by their number, one line
  std::string text;
  for (int i = 0; i < 60000; ++i) text += "uav_count: 4\n";
  const ConfigError many = expectConfigError([&] { parseScenario(text, "<t>"); });
  ASSERT_EQ(many.problems().size(), 1u) << many.problems()[0];
  EXPECT_EQ(many.problems()[0], "has more than 2000 keys: not a scenario file");
  // and 1500 duplicate keys (under the key limit) are one merged problem per distinct message, at most 21 lines
  std::string dup;
  for (int i = 0; i < 1500; ++i) dup += "uav_count: 4\n";
  EXPECT_LE(expectConfigError([&] { parseScenario(dup, "<t>"); }).problems().size(), 21u);
}

TEST(ScenarioYaml, GivenAScenarioWithEveryFieldChanged_WhenDumpedAndParsed_ThenItIsIdentical) {
  // GIVEN a valid scenario that differs from the defaults everywhere
  const Scenario original = everyFieldChanged();
  // WHEN it is written and read back
  const std::string yaml = scenarioToYaml(original);
  const Scenario reread = parseScenario(yaml, "dump");
  // THEN the dump of the result is the same text, bit for bit, and differs from the defaults
  EXPECT_EQ(scenarioToYaml(reread), yaml);
  EXPECT_NE(yaml, scenarioToYaml(Scenario{}));
  EXPECT_EQ(reread.seed, original.seed);
  EXPECT_EQ(reread.formation.spacing_m, original.formation.spacing_m);
  EXPECT_EQ(reread.gnss.keep_uavs, original.gnss.keep_uavs);
  ASSERT_EQ(reread.gnss.windows.size(), original.gnss.windows.size());
  for (std::size_t i = 0; i < original.gnss.windows.size(); ++i) {
    EXPECT_EQ(reread.gnss.windows[i].uav, original.gnss.windows[i].uav) << i;
    EXPECT_EQ(reread.gnss.windows[i].start_s, original.gnss.windows[i].start_s) << i;
    EXPECT_EQ(reread.gnss.windows[i].end_s, original.gnss.windows[i].end_s) << i;
  }
  EXPECT_EQ(reread.agent.formation.radius_m, 11.0);  // written explicitly, so not replaced by the spacing
  // AND it reads like a scenario file
  EXPECT_TRUE(contains(yaml, "uav_count: 12")) << yaml;
  EXPECT_TRUE(contains(yaml, "\nmps:\n")) << yaml;
  EXPECT_TRUE(contains(yaml, "  ids: false")) << yaml;
  EXPECT_TRUE(contains(yaml, "  keep_uavs: [0, 11]")) << yaml;
  EXPECT_TRUE(contains(yaml, "\n  windows:  ")) << yaml;  // followed by the aligned comment
  EXPECT_TRUE(contains(yaml,
                       "\n    - {uav: 3, start_s: 20.0, end_s: 40.0}\n"
                       "    - {uav: 11, start_s: 0.30000000000000004, end_s: .inf}\n"
                       "    - {uav: 3, start_s: 35.5, end_s: 1.0e+05}\n"))
      << yaml;
  EXPECT_TRUE(contains(yaml, "  mode: realtime")) << yaml;
  EXPECT_TRUE(contains(yaml, "\nagent:")) << yaml;
  EXPECT_TRUE(contains(yaml, "\n  formation:\n    radius_m: 11.0")) << yaml;
  // AND the defaults round-trip too, including the infinite dropout end
  const std::string defaults = scenarioToYaml(Scenario{});
  EXPECT_TRUE(contains(defaults, "dropout_end_s: .inf")) << defaults;
  EXPECT_TRUE(contains(defaults, "\n  windows: []  ")) << defaults;
  EXPECT_EQ(scenarioToYaml(parseScenario(defaults, "dump")), defaults);
}

TEST(ScenarioHelp, GivenTheParameterDescription_ThenItListsEveryKeyAndTheAgentTable) {
  const std::string help = describeScenarioParameters();
  for (const char* key : {"uav_count", "seed", "duration_s", "formation.spacing_m", "dynamics.heading", "wind.gust_std",
                          "imu.bias_std", "mps.ids", "mps.miss_probability", "mps.noise_model", "gnss.dropout_start_s",
                          "gnss.dropout_end_s", "gnss.keep_uavs", "gnss.windows", "clock.mode", "agent.k",
                          "agent.circle_fit", "formation.circle_fit", "focal.q_scale"}) {
    EXPECT_TRUE(contains(help, key)) << key;
  }
  EXPECT_TRUE(contains(help, "must each divide dynamics.rate_hz")) << help;
  EXPECT_TRUE(contains(help, "gnss.windows: extra outages of single UAVs")) << help;
}

}  // namespace
}  // namespace swa::sim
