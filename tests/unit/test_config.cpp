// AgentConfig loading, validation, overrides and recording (agent/include/swa/agent/config_io.h).

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "scratch.h"
#include "swa/agent/config.h"
#include "swa/agent/config_io.h"

namespace swa::agent {
namespace {

// Field by field, written out by hand so that a field missing from the parameter table is caught.
void expectSameConfig(const AgentConfig& a, const AgentConfig& b) {
  EXPECT_EQ(a.mode, b.mode);
  EXPECT_EQ(a.surroundings.q_pos_m2, b.surroundings.q_pos_m2);
  EXPECT_EQ(a.surroundings.q_vel_m2ps2, b.surroundings.q_vel_m2ps2);
  EXPECT_EQ(a.surroundings.q_acc_m2ps4, b.surroundings.q_acc_m2ps4);
  EXPECT_EQ(a.surroundings.q_ref_dt_s, b.surroundings.q_ref_dt_s);
  EXPECT_EQ(a.surroundings.r_det_m2, b.surroundings.r_det_m2);
  EXPECT_EQ(a.surroundings.init_vel_var_m2ps2, b.surroundings.init_vel_var_m2ps2);
  EXPECT_EQ(a.surroundings.init_acc_var_m2ps4, b.surroundings.init_acc_var_m2ps4);
  EXPECT_EQ(a.surroundings.confirm_hits, b.surroundings.confirm_hits);
  EXPECT_EQ(a.surroundings.track_timeout_s, b.surroundings.track_timeout_s);
  EXPECT_EQ(a.surroundings.tentative_timeout_s, b.surroundings.tentative_timeout_s);
  EXPECT_EQ(a.surroundings.gate_probability, b.surroundings.gate_probability);
  EXPECT_EQ(a.formation.radius_m, b.formation.radius_m);
  EXPECT_EQ(a.formation.neighbourhood, b.formation.neighbourhood);
  EXPECT_EQ(a.formation.k, b.formation.k);
  EXPECT_EQ(a.formation.sensing_range_m, b.formation.sensing_range_m);
  EXPECT_EQ(a.formation.circle_fit, b.formation.circle_fit);
  EXPECT_EQ(a.formation.max_edge_factor, b.formation.max_edge_factor);
  EXPECT_EQ(a.formation.far_neighbour_weight, b.formation.far_neighbour_weight);
  EXPECT_EQ(a.focal.bias_window_s, b.focal.bias_window_s);
  EXPECT_EQ(a.focal.bias_freeze_speed_mps, b.focal.bias_freeze_speed_mps);
  EXPECT_EQ(a.focal.bias_freeze_hold_s, b.focal.bias_freeze_hold_s);
  EXPECT_EQ(a.focal.tau_s, b.focal.tau_s);
  EXPECT_EQ(a.focal.q_pos_m2, b.focal.q_pos_m2);
  EXPECT_EQ(a.focal.q_vel_m2ps2, b.focal.q_vel_m2ps2);
  EXPECT_EQ(a.focal.q_acc_m2ps4, b.focal.q_acc_m2ps4);
  EXPECT_EQ(a.focal.q_scale, b.focal.q_scale);
  EXPECT_EQ(a.focal.q_ref_dt_s, b.focal.q_ref_dt_s);
  EXPECT_EQ(a.focal.r_pos_m2, b.focal.r_pos_m2);
  EXPECT_EQ(a.focal.r_acc_m2ps4, b.focal.r_acc_m2ps4);
  EXPECT_EQ(a.focal.q_c_mps2, b.focal.q_c_mps2);
  EXPECT_EQ(a.focal.frame_timeout_s, b.focal.frame_timeout_s);
  EXPECT_EQ(a.control.k_p, b.control.k_p);
  EXPECT_EQ(a.control.k_v, b.control.k_v);
  EXPECT_EQ(a.control.v_max_mps, b.control.v_max_mps);
  EXPECT_EQ(a.anchor.gain, b.anchor.gain);
  EXPECT_EQ(a.anchor.gnss_min_std_m, b.anchor.gnss_min_std_m);
  EXPECT_EQ(a.limits.max_detections, b.limits.max_detections);
  EXPECT_EQ(a.limits.max_target_id, b.limits.max_target_id);
  EXPECT_EQ(a.limits.max_tilt_rad, b.limits.max_tilt_rad);
  EXPECT_EQ(a.limits.max_abs_position_m, b.limits.max_abs_position_m);
  EXPECT_EQ(a.sensor.fov_deg, b.sensor.fov_deg);
  EXPECT_EQ(a.sensor.mount_deg, b.sensor.mount_deg);
  EXPECT_EQ(a.sensor.input, b.sensor.input);
  EXPECT_EQ(a.sensor.detector_frame, b.sensor.detector_frame);
  EXPECT_EQ(a.sensor.detector_yaw_deg, b.sensor.detector_yaw_deg);
  EXPECT_EQ(a.sensor.detector_x_m, b.sensor.detector_x_m);
  EXPECT_EQ(a.sensor.detector_y_m, b.sensor.detector_y_m);
  EXPECT_EQ(a.sensor.detector_classes, b.sensor.detector_classes);
  EXPECT_EQ(a.mission.start, b.mission.start);
  EXPECT_EQ(a.mission.start_s, b.mission.start_s);
  EXPECT_EQ(a.mission.max_speed_mps, b.mission.max_speed_mps);
  EXPECT_EQ(a.mission.response_s, b.mission.response_s);
  ASSERT_EQ(a.mission.legs.size(), b.mission.legs.size());
  for (std::size_t i = 0; i < a.mission.legs.size(); ++i) {
    EXPECT_EQ(a.mission.legs[i].velocity_mps, b.mission.legs[i].velocity_mps) << i;
    EXPECT_EQ(a.mission.legs[i].duration_s, b.mission.legs[i].duration_s) << i;
  }
}

// Every field different from its default and valid; awkward binary fractions test exact round trips.
AgentConfig everyFieldChanged() {
  AgentConfig c;
  c.mode = Mode::kAnchored;
  c.surroundings.q_pos_m2 = 0.1 + 0.2;
  c.surroundings.q_vel_m2ps2 = 1.0 / 3.0;
  c.surroundings.q_acc_m2ps4 = 2e-7;
  c.surroundings.q_ref_dt_s = 0.02;
  c.surroundings.r_det_m2 = 0.05;
  c.surroundings.init_vel_var_m2ps2 = 2.5;
  c.surroundings.init_acc_var_m2ps4 = 0.75;
  c.surroundings.confirm_hits = 5;
  c.surroundings.track_timeout_s = 1.5;
  c.surroundings.tentative_timeout_s = 0.4;
  c.surroundings.gate_probability = 0.999;
  c.formation.radius_m = 12.345678901234567;
  c.formation.neighbourhood = NeighbourhoodRule::kKNearest;  // so k is used (max_edge_factor then is not)
  c.formation.k = 4;
  c.formation.sensing_range_m = 55.5;
  c.formation.circle_fit = CircleFit::kAlgebraic;
  c.focal.tau_s = 3.1;
  c.focal.q_pos_m2 = 0.06;
  c.focal.q_vel_m2ps2 = 0.7;
  c.focal.q_acc_m2ps4 = 6.0;
  c.focal.q_scale = 0.5;
  c.focal.q_ref_dt_s = 0.005;
  c.focal.r_pos_m2 = 0.025;
  c.focal.r_acc_m2ps4 = 1.5;
  c.focal.q_c_mps2 = 9.81;
  c.focal.frame_timeout_s = 3.0;
  c.control.k_p = 0.45;
  c.control.k_v = 0.9;
  c.control.v_max_mps = 3.0;
  c.anchor.gain = 0.5;
  c.sensor.input = DetectionInput::kVisionMsgs;
  c.sensor.detector_frame = "uav1/front_lidar";
  c.sensor.detector_yaw_deg = 90.5;
  c.sensor.detector_x_m = 0.25;
  c.sensor.detector_y_m = -0.125;
  c.sensor.detector_classes = "uav,drone";
  c.anchor.gnss_min_std_m = 0.1;
  c.limits.max_detections = 128;
  c.limits.max_target_id = 5000;
  c.limits.max_tilt_rad = 0.6;
  c.limits.max_abs_position_m = 2.5e5;
  c.mission.start = MissionStart::kTime;
  c.mission.start_s = 2.5;
  c.mission.response_s = 0.35;
  c.mission.max_speed_mps = 4.5;
  c.mission.legs = {{Vec2(0.1 + 0.2, -1.0 / 3.0), 7.25}, {Vec2(-4, 0), 1e-3}};
  return c;
}

// The ConfigError thrown by `action`; fails the test if none is thrown.
ConfigError expectConfigError(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a ConfigError";
  return ConfigError("<none>", {});
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The one problem that mentions `key`; fails the test unless exactly one does.
std::string problemAbout(const ConfigError& error, const std::string& key) {
  std::vector<std::string> matches;
  for (const std::string& p : error.problems()) {
    if (contains(p, key)) matches.push_back(p);
  }
  EXPECT_EQ(matches.size(), 1u) << "problems mentioning '" << key << "':\n" << error.what();
  return matches.empty() ? std::string() : matches.front();
}

using testing::ScratchFile;

// deploy/config/agent.yaml, found from this file's location (tests/unit/test_config.cpp).
std::string exampleConfigPath() {
  return (std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "deploy" / "config" / "agent.yaml")
      .lexically_normal()
      .string();
}

// "section.key" for every key line of a YAML text in the layout toYaml writes (two-space nesting).
std::set<std::string> keysOf(const std::string& yaml) {
  std::set<std::string> keys;
  std::istringstream lines(yaml);
  std::string line;
  std::string section;
  while (std::getline(lines, line)) {
    line = line.substr(0, line.find('#'));
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const bool nested = line.rfind("  ", 0) == 0;
    const std::string name = line.substr(nested ? 2 : 0, colon - (nested ? 2 : 0));
    const bool has_value = line.find_first_not_of(' ', colon + 1) != std::string::npos;
    if (nested) {
      keys.insert(section + "." + name);
    } else if (has_value) {
      keys.insert(name);
    } else {
      section = name;
    }
  }
  return keys;
}

// ------------------------------------------------------------------------------------------------------------

TEST(AgentConfigDefaults, GivenADefaultConfig_ThenItHoldsTableI) {
  // GIVEN a default-constructed configuration
  const AgentConfig c;
  // THEN the values are the paper's Table I (and DESIGN.md §3 where it deliberately deviates)
  EXPECT_EQ(c.mode, Mode::kSwa);
  EXPECT_DOUBLE_EQ(c.formation.radius_m, 10.0);
  EXPECT_EQ(c.formation.k, 3);
  EXPECT_EQ(c.formation.circle_fit, CircleFit::kFixedRadius);
  // DESIGN §3.2-§3.4 rules measured to beat the paper's: Gabriel neighbours, weighted fit, IMU-bias removal
  EXPECT_EQ(c.formation.neighbourhood, NeighbourhoodRule::kGabriel);
  EXPECT_DOUBLE_EQ(c.formation.far_neighbour_weight, 0.2);
  EXPECT_DOUBLE_EQ(c.formation.max_edge_factor, 1.3);
  EXPECT_DOUBLE_EQ(c.focal.bias_window_s, 30.0);
  EXPECT_DOUBLE_EQ(c.focal.tau_s, 2.8);
  EXPECT_DOUBLE_EQ(c.control.k_p, 0.7);  // tuned to the simulator's velocity lag (Table I: 0.5)
  EXPECT_DOUBLE_EQ(c.control.k_v, 0.63);
  EXPECT_DOUBLE_EQ(c.surroundings.q_pos_m2, 1e-3);
  EXPECT_DOUBLE_EQ(c.surroundings.q_vel_m2ps2, 1e-2);
  EXPECT_DOUBLE_EQ(c.surroundings.q_acc_m2ps4, 1e-1);
  EXPECT_DOUBLE_EQ(c.surroundings.r_det_m2, 0.1);
  // Q_f and R_c are the ANEES-tuned values (Table I's are conservative, see config.h and test_focal_consistency)
  EXPECT_DOUBLE_EQ(c.focal.q_pos_m2, 1.5e-4);
  EXPECT_DOUBLE_EQ(c.focal.q_vel_m2ps2, 1.7e-4);
  EXPECT_DOUBLE_EQ(c.focal.q_acc_m2ps4, 0.1);
  EXPECT_DOUBLE_EQ(c.focal.q_scale, 1.0);
  EXPECT_DOUBLE_EQ(c.focal.r_pos_m2, 0.1);
  EXPECT_DOUBLE_EQ(c.focal.r_acc_m2ps4, 2.25);
  EXPECT_DOUBLE_EQ(c.focal.q_c_mps2, 6.35);
  // AND they satisfy the declared bounds and cross-field constraints
  EXPECT_NO_THROW(validateAgentConfig(c));
}

TEST(AgentConfigDefaults, GivenTheEnums_ThenToStringGivesTheYamlSpelling) {
  EXPECT_EQ(toString(Mode::kSwa), "swa");
  EXPECT_EQ(toString(Mode::kStandalone), "standalone");
  EXPECT_EQ(toString(Mode::kAnchored), "anchored");
  EXPECT_EQ(toString(CircleFit::kFixedRadius), "fixed_radius");
  EXPECT_EQ(toString(CircleFit::kAlgebraic), "algebraic");
  EXPECT_EQ(toString(NeighbourhoodRule::kGabriel), "gabriel");
  EXPECT_EQ(toString(NeighbourhoodRule::kKNearest), "k_nearest");
}

TEST(AgentConfigParse, GivenAnEmptyOrCommentOnlyText_WhenParsed_ThenAllDefaults) {
  expectSameConfig(parseAgentConfig(""), AgentConfig{});
  expectSameConfig(parseAgentConfig("# nothing set\n\n"), AgentConfig{});
  // an empty section keeps its defaults too
  expectSameConfig(parseAgentConfig("formation:\n"), AgentConfig{});
}

TEST(AgentConfigParse, GivenAPartialFile_WhenLoaded_ThenOnlyItsKeysChange) {
  // GIVEN a file that sets three keys in two sections and the mode
  const ScratchFile file(
      "mode: anchored\n"
      "formation:\n"
      "  radius_m: 12.5\n"
      "  neighbourhood: k_nearest\n"
      "  k: 4\n"
      "control:\n"
      "  k_p: 0.8\n");
  // WHEN it is loaded
  const AgentConfig loaded = loadAgentConfig(file.path());
  // THEN those keys have the file's values
  EXPECT_EQ(loaded.mode, Mode::kAnchored);
  EXPECT_EQ(loaded.formation.radius_m, 12.5);
  EXPECT_EQ(loaded.formation.k, 4);
  EXPECT_EQ(loaded.control.k_p, 0.8);
  // AND everything else is the default
  AgentConfig expected;
  expected.mode = Mode::kAnchored;
  expected.formation.radius_m = 12.5;
  expected.formation.neighbourhood = NeighbourhoodRule::kKNearest;
  expected.formation.k = 4;
  expected.control.k_p = 0.8;
  expectSameConfig(loaded, expected);
}

TEST(AgentConfigParse, GivenNumbersInYamlSpellings_WhenParsed_ThenTheyAreRead) {
  const AgentConfig c = parseAgentConfig(
      "surroundings: {q_pos_m2: 2e-3, q_vel_m2ps2: +0.5, confirm_hits: 4.0}\n"
      "limits: {max_detections: 1024, max_target_id: 1e3}\n");
  EXPECT_EQ(c.surroundings.q_pos_m2, 2e-3);
  EXPECT_EQ(c.surroundings.q_vel_m2ps2, 0.5);
  EXPECT_EQ(c.surroundings.confirm_hits, 4);
  EXPECT_EQ(c.limits.max_detections, 1024u);
  EXPECT_EQ(c.limits.max_target_id, 1000);
}

TEST(AgentConfigParse, GivenAFileWithFiveDistinctProblems_WhenLoaded_ThenOneErrorListsAllFive) {
  // GIVEN a file with a bad enum, a wrong type, an unknown key, an out-of-range value and a NaN
  const ScratchFile file(
      "mode: swarm\n"
      "formation:\n"
      "  radius_m: ten\n"
      "  raduis_m: 5\n"
      "control:\n"
      "  k_p: -1\n"
      "focal:\n"
      "  tau_s: .nan\n");
  // WHEN it is loaded
  const ConfigError error = expectConfigError([&] { loadAgentConfig(file.path()); });
  // THEN exactly five problems are reported at once, each naming its key
  ASSERT_EQ(error.problems().size(), 5u) << error.what();
  EXPECT_EQ(error.source(), file.path());

  const std::string mode = problemAbout(error, "mode =");
  EXPECT_TRUE(contains(mode, "'swarm'")) << mode;
  EXPECT_TRUE(contains(mode, "swa, standalone, anchored")) << mode;
  EXPECT_TRUE(contains(mode, "line 1")) << mode;

  const std::string radius = problemAbout(error, "formation.radius_m =");
  EXPECT_TRUE(contains(radius, "'ten' is not a number")) << radius;
  EXPECT_TRUE(contains(radius, "line 3")) << radius;

  const std::string unknown = problemAbout(error, "formation.raduis_m");
  EXPECT_TRUE(contains(unknown, "unknown key")) << unknown;
  EXPECT_TRUE(contains(unknown, "did you mean 'formation.radius_m'?")) << unknown;

  const std::string k_p = problemAbout(error, "control.k_p");
  EXPECT_TRUE(contains(k_p, "control.k_p = -1 is out of range [0, 20] 1/s")) << k_p;
  EXPECT_TRUE(contains(k_p, "line 6")) << k_p;

  const std::string tau = problemAbout(error, "focal.tau_s");
  EXPECT_TRUE(contains(tau, "focal.tau_s = .nan is not a finite number")) << tau;

  // AND what() has one line per problem, each prefixed by the file path
  std::istringstream lines(error.what());
  std::string line;
  std::size_t count = 0;
  while (std::getline(lines, line)) {
    EXPECT_EQ(line.rfind(file.path() + ": ", 0), 0u) << line;
    ++count;
  }
  EXPECT_EQ(count, 5u);
}

TEST(AgentConfigParse, GivenValuesOfTheWrongShape_WhenParsed_ThenEachIsATypeError) {
  const ConfigError error = expectConfigError([] {
    parseAgentConfig(
        "formation:\n"
        "  radius_m: {value: 10}\n"    // a map where a number is expected
        "  k: 2.5\n"                   // an integer key given a non-integer
        "  sensing_range_m: \"40\"\n"  // a quoted string is not a number
        "  circle_fit: [algebraic]\n"  // a sequence where a choice is expected
        "control: 3\n"                 // a scalar where a section map is expected
        "focal:\n"
        "  tau_s: -.inf\n"  // infinity
        "  q_scale:\n");    // no value at all
  });
  ASSERT_EQ(error.problems().size(), 7u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "formation.radius_m"), "got a map"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.k "), "formation.k = 2.5 is not an integer"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.sensing_range_m"), "is a string"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.circle_fit"), "got a sequence"));
  EXPECT_TRUE(contains(problemAbout(error, "'control'"), "must be a map"));
  EXPECT_TRUE(contains(problemAbout(error, "focal.tau_s"), "-.inf is not a finite number"));
  EXPECT_TRUE(contains(problemAbout(error, "focal.q_scale"), "has no value"));
}

TEST(AgentConfigParse, GivenOpenAndIntegerBounds_WhenViolated_ThenTheBoundAndUnitAreNamed) {
  const ConfigError error = expectConfigError([] {
    parseAgentConfig(
        "formation: {radius_m: 0, k: 17}\n"
        "surroundings: {gate_probability: 1, confirm_hits: 0}\n"
        "limits: {max_detections: 2000}\n");
  });
  ASSERT_EQ(error.problems().size(), 5u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "formation.radius_m"), "= 0 is out of range (0, 1000] m"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.k "), "= 17 is out of range [1, 16]"));
  EXPECT_TRUE(contains(problemAbout(error, "surroundings.gate_probability"), "= 1 is out of range (0, 1)"));
  EXPECT_TRUE(contains(problemAbout(error, "surroundings.confirm_hits"), "= 0 is out of range [1, 20]"));
  EXPECT_TRUE(contains(problemAbout(error, "limits.max_detections"), "= 2000 is out of range [1, 1024]"));
}

TEST(AgentConfigParse, GivenAnUnknownKeyNearAKnownOne_ThenTheHintNamesIt) {
  // typo in a section name
  ConfigError error = expectConfigError([] { parseAgentConfig("formaton:\n  radius_m: 5\n"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "unknown key 'formaton' (did you mean 'formation'?)"));
  // right name in the wrong section
  error = expectConfigError([] { parseAgentConfig("focal:\n  radius_m: 5\n"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "did you mean 'formation.radius_m'?"));
  // nothing close: no hint
  error = expectConfigError([] { parseAgentConfig("control:\n  banana: 1\n"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "unknown key 'control.banana'"));
  EXPECT_FALSE(contains(error.problems()[0], "did you mean"));
}

TEST(AgentConfigParse, GivenDuplicateOrDottedKeys_ThenTheyAreRejected) {
  const ConfigError error = expectConfigError([] {
    parseAgentConfig(
        "control:\n  k_p: 0.5\n  k_p: 0.6\n"
        "formation.radius_m: 12\n");
  });
  ASSERT_EQ(error.problems().size(), 2u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "control.k_p"), "duplicate key"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.radius_m"), "must be written nested"));
}

TEST(AgentConfigParse, GivenViolatedCrossFieldConstraints_ThenTheyAreReportedWithTheFieldErrors) {
  // GIVEN a tentative timeout longer than the confirmed-track timeout, a sensing range inside the formation
  // radius, and an unrelated out-of-range value
  const ConfigError error = expectConfigError([] {
    parseAgentConfig(
        "surroundings: {track_timeout_s: 0.5, tentative_timeout_s: 0.8}\n"
        "formation: {radius_m: 50}\n"
        "control: {v_max_mps: 0}\n");
  });
  // THEN all three are in the same error
  ASSERT_EQ(error.problems().size(), 3u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "surroundings.tentative_timeout_s"),
                       "surroundings.tentative_timeout_s = 0.8 must be <= surroundings.track_timeout_s = 0.5"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.sensing_range_m"),
                       "formation.radius_m = 50 must be < formation.sensing_range_m = 40"));
  EXPECT_TRUE(contains(problemAbout(error, "control.v_max_mps"), "(0, 50] m/s"));
}

TEST(AgentConfigParse, GivenARelationWhoseFieldIsInvalid_ThenOnlyTheFieldErrorIsReported) {
  const ConfigError error =
      expectConfigError([] { parseAgentConfig("surroundings: {track_timeout_s: -1, tentative_timeout_s: 0.8}\n"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "surroundings.track_timeout_s = -1 is out of range (0, 60] s"));
}

TEST(AgentConfigParse, GivenInvalidYaml_ThenTheErrorGivesLineAndColumn) {
  const ConfigError error = expectConfigError([] { parseAgentConfig("formation:\n  radius_m: [10\n", "bad.yaml"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "invalid YAML at line ")) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], ", column ")) << error.what();
  EXPECT_EQ(std::string(error.what()).rfind("bad.yaml: ", 0), 0u) << error.what();
}

TEST(AgentConfigParse, GivenATopLevelThatIsNotAMap_ThenItIsRejected) {
  ConfigError error = expectConfigError([] { parseAgentConfig("just a string\n"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "top level must be a map")) << error.what();
  error = expectConfigError([] { parseAgentConfig("- formation\n- control\n"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "got a sequence")) << error.what();
}

TEST(AgentConfigLoad, GivenAMissingFile_ThenTheErrorNamesThePath) {
  const std::string path = "/nonexistent/swa/agent.yaml";
  const ConfigError error = expectConfigError([&] { loadAgentConfig(path); });
  ASSERT_EQ(error.problems().size(), 1u);
  EXPECT_EQ(error.source(), path);
  EXPECT_EQ(std::string(error.what()), path + ": configuration file does not exist");
}

TEST(AgentConfigLoad, GivenTheExampleFile_ThenItParsesToTheDefaultsAndListsEveryKey) {
  // GIVEN deploy/config/agent.yaml
  const std::string path = exampleConfigPath();
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  // WHEN it is loaded
  const AgentConfig loaded = loadAgentConfig(path);
  // THEN it is exactly the default configuration
  expectSameConfig(loaded, AgentConfig{});
  EXPECT_EQ(toYaml(loaded), toYaml(AgentConfig{}));
  // AND it gives every key the defaults use, none missing and none extra, and names the three they ignore (k of
  // k_nearest, anchor.* of anchored mode) as comments, as the dump does: giving them would be an error
  std::ifstream file(path);
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  EXPECT_EQ(keysOf(text), keysOf(toYaml(AgentConfig{})));
  EXPECT_EQ(keysOf(text).size(), 53u);
  EXPECT_TRUE(contains(text, "  # k: 3 ")) << text;
  EXPECT_TRUE(contains(text, "#   gain: 0.2 ")) << text;
  EXPECT_TRUE(contains(text, "#   gnss_min_std_m: 0.05 ")) << text;
}

TEST(AgentConfigOverride, GivenSetArguments_WhenApplied_ThenTheyOverrideTheFileValues) {
  // GIVEN a config loaded from text
  const AgentConfig base = parseAgentConfig("formation: {radius_m: 12}\n");
  // WHEN --set arguments are applied
  const AgentConfig c =
      applyOverrides(base, {"formation.neighbourhood=k_nearest", "formation.k=2", "formation.radius_m=8.5",
                            "mode=anchored", "formation.circle_fit=algebraic", "limits.max_detections=32"});
  // THEN they win, and the rest is untouched
  AgentConfig expected;
  expected.formation.neighbourhood = NeighbourhoodRule::kKNearest;
  expected.formation.k = 2;
  expected.formation.radius_m = 8.5;
  expected.mode = Mode::kAnchored;
  expected.formation.circle_fit = CircleFit::kAlgebraic;
  expected.limits.max_detections = 32;
  expectSameConfig(c, expected);
}

TEST(AgentConfigOverride, GivenOverridesThatOnlyTogetherSatisfyARelation_ThenTheyAreAccepted) {
  // raising the tentative timeout above the default track timeout is fine once the latter is raised too
  const AgentConfig c =
      applyOverrides(AgentConfig{}, {"surroundings.tentative_timeout_s=2", "surroundings.track_timeout_s=3"});
  EXPECT_EQ(c.surroundings.tentative_timeout_s, 2.0);
  EXPECT_EQ(c.surroundings.track_timeout_s, 3.0);
}

TEST(AgentConfigOverride, GivenBadSetArguments_ThenAllAreReportedTogether) {
  // GIVEN one malformed entry, one unknown key, one out-of-range value, one wrong type, one bad enum
  const std::vector<std::string> args = {"formationk2",     "formation.kk=2", "control.k_p=-1",
                                         "formation.k=two", "mode=swarm",     "focal.tau_s=3.0"};
  // WHEN they are applied
  const ConfigError error = expectConfigError([&] { applyOverrides(AgentConfig{}, args); });
  // THEN one error lists the five problems, prefixed by --set
  ASSERT_EQ(error.problems().size(), 5u) << error.what();
  EXPECT_EQ(error.source(), "--set");
  EXPECT_TRUE(contains(problemAbout(error, "formationk2"), "malformed override 'formationk2'; expected key=value"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.kk"), "did you mean 'formation.k'?"));
  EXPECT_TRUE(contains(problemAbout(error, "control.k_p"), "control.k_p = -1 is out of range [0, 20] 1/s"));
  EXPECT_TRUE(contains(problemAbout(error, "formation.k ="), "'two' is not a number"));
  EXPECT_TRUE(contains(problemAbout(error, "mode"), "expected one of: swa, standalone, anchored"));
  EXPECT_EQ(std::string(error.what()).rfind("--set: ", 0), 0u);
}

TEST(AgentConfigOverride, GivenASingleBadOverride_ThenTheConfigIsUnchanged) {
  AgentConfig c;
  applyOverride(c, "focal.q_scale", "1");
  EXPECT_EQ(c.focal.q_scale, 1.0);

  const ConfigError error = expectConfigError([&] { applyOverride(c, "formation.sensing_range_m", "5"); });
  ASSERT_EQ(error.problems().size(), 1u) << error.what();
  EXPECT_TRUE(contains(error.problems()[0], "must be < formation.sensing_range_m = 5"));
  EXPECT_EQ(c.formation.sensing_range_m, 40.0);

  const ConfigError section = expectConfigError([&] { applyOverride(c, "formation", "3"); });
  ASSERT_EQ(section.problems().size(), 1u);
  EXPECT_TRUE(contains(section.problems()[0], "'formation' is a group of parameters"));
}

TEST(AgentConfigYaml, GivenAConfigWithEveryFieldChanged_WhenDumpedAndParsed_ThenItIsIdentical) {
  // GIVEN a valid configuration that differs from the defaults in every field
  const AgentConfig original = everyFieldChanged();
  ASSERT_NO_THROW(validateAgentConfig(original));
  // WHEN it is written with toYaml and read back
  const std::string yaml = toYaml(original);
  const AgentConfig reread = parseAgentConfig(yaml, "toYaml");
  // THEN every field is bit-identical and the dump is stable
  expectSameConfig(reread, original);
  EXPECT_EQ(toYaml(reread), yaml);
  EXPECT_NE(yaml, toYaml(AgentConfig{}));
  // AND the dump is readable: nested keys, enum spellings, reals that YAML 1.1 readers see as floats
  EXPECT_TRUE(contains(yaml, "mode: anchored")) << yaml;
  EXPECT_TRUE(contains(yaml, "\nformation:\n  radius_m: 12.3456789012345")) << yaml;
  EXPECT_TRUE(contains(yaml, "  circle_fit: algebraic")) << yaml;
  EXPECT_TRUE(contains(yaml, "  q_acc_m2ps4: 2.0e-07")) << yaml;
  EXPECT_TRUE(contains(yaml, "  max_detections: 128")) << yaml;
  EXPECT_TRUE(contains(yaml, "  detector_frame: \"uav1/front_lidar\"")) << yaml;
}

TEST(AgentConfigParse, GivenADetectorFrameOrClassListThatIsNoName_ThenItIsRefused) {
  // GIVEN text keys with characters no frame id or class id has, or far too long
  const ConfigError error = expectConfigError([&] {
    parseAgentConfig(
        "sensor:\n  input: vision_msgs\n  detector_frame: \"uav1/lidar; rm -rf\"\n"
        "  detector_classes: [uav, drone]\n");
  });
  // THEN each is a problem that says what is expected
  ASSERT_EQ(error.problems().size(), 2u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "detector_frame"), "expected a frame id of letters, digits and _ . / -"));
  EXPECT_TRUE(contains(problemAbout(error, "detector_classes"), "must be class ids separated by commas"))
      << error.what();
  const ConfigError long_one = expectConfigError([&] {
    applyOverrides(AgentConfig{}, {"sensor.input=uvdar", "sensor.detector_frame=" + std::string(300, 'a')});
  });
  EXPECT_EQ(long_one.problems().size(), 1u) << long_one.what();
  // AND a good one, and the empty text, are read as written
  const AgentConfig c =
      parseAgentConfig("sensor: {input: vision_msgs, detector_frame: uav2/lidar, detector_classes: \"\"}\n");
  EXPECT_EQ(c.sensor.detector_frame, "uav2/lidar");
  EXPECT_EQ(c.sensor.detector_classes, "");
}

TEST(AgentConfigApplies, GivenDetectorKeysThatChangeNothing_ThenEachIsAnErrorThatSaysWhy) {
  // GIVEN a mount without a detector frame, a class list for UVDAR, and a detector frame with SWA's own detections
  const ConfigError error = expectConfigError(
      [&] { parseAgentConfig("sensor:\n  input: uvdar\n  detector_yaw_deg: 90\n  detector_classes: uav\n"); });
  const ConfigError swa = expectConfigError([&] { parseAgentConfig("sensor: {detector_frame: lidar}\n"); });
  // THEN each is refused, naming the case it applies to
  ASSERT_EQ(error.problems().size(), 2u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "detector_yaw_deg"), "applies to a detector in its own frame only"));
  EXPECT_TRUE(contains(problemAbout(error, "detector_classes"), "applies to vision_msgs detections only"));
  ASSERT_EQ(swa.problems().size(), 1u) << swa.what();
  EXPECT_TRUE(contains(swa.problems()[0], "applies to a real detector's messages only")) << swa.what();
}

TEST(AgentConfigYaml, GivenTheDefaults_WhenDumped_ThenEveryKeyIsPresentWithItsUnit) {
  const std::string yaml = toYaml(AgentConfig{});
  EXPECT_EQ(keysOf(yaml).size(), 53u);
  EXPECT_TRUE(contains(yaml, "k_p: 0.7")) << yaml;
  // AND the three keys the defaults ignore are written as comments that say so
  EXPECT_TRUE(contains(yaml, "  # k: 3")) << yaml;
  EXPECT_TRUE(contains(yaml, "not used: the k_nearest rule only")) << yaml;
  EXPECT_TRUE(contains(yaml, "  # gain: 0.2")) << yaml;
  EXPECT_TRUE(contains(yaml, "  # gnss_min_std_m: 0.05")) << yaml;
  EXPECT_TRUE(contains(yaml, "  # detector_frame: \"\"")) << yaml;
  EXPECT_TRUE(contains(yaml, "# 1/s")) << yaml;
  expectSameConfig(parseAgentConfig(yaml), AgentConfig{});
}

TEST(AgentConfigValidate, GivenAnInvalidConfigBuiltInCode_ThenValidationListsEveryViolation) {
  AgentConfig c;
  c.formation.k = 0;
  c.control.k_v = std::nan("");
  c.limits.max_detections = 0;
  const ConfigError error = expectConfigError([&] { validateAgentConfig(c, "scenario"); });
  ASSERT_EQ(error.problems().size(), 3u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "formation.k"), "= 0 is out of range [1, 16]"));
  EXPECT_TRUE(contains(problemAbout(error, "control.k_v"), "is not a finite number"));
  EXPECT_TRUE(contains(problemAbout(error, "limits.max_detections"), "= 0 is out of range [1, 1024]"));
}

// ===============================================================================================================
// Keys the chosen mode ignores

TEST(AgentConfigApplies, GivenKWithTheGabrielRule_ThenItIsAnErrorThatSaysWhy) {
  // GIVEN formation.k in a file whose rule is gabriel (the default), and the same as a --set
  const ConfigError file = expectConfigError([] { parseAgentConfig("formation:\n  k: 2\n", "a.yaml"); });
  const ConfigError set = expectConfigError([] { applyOverrides(AgentConfig{}, {"formation.k=2"}); });
  // THEN each says that k applies to the k_nearest rule only, where it was given, and what to change
  ASSERT_EQ(file.problems().size(), 1u) << file.what();
  EXPECT_TRUE(contains(file.problems()[0],
                       "formation.k applies to the k_nearest rule only "
                       "(formation.neighbourhood is gabriel)"))
      << file.what();
  EXPECT_TRUE(contains(file.problems()[0], "(line 2, column 6)")) << file.what();
  ASSERT_EQ(set.problems().size(), 1u) << set.what();
  EXPECT_TRUE(contains(set.problems()[0], "formation.k applies to the k_nearest rule only")) << set.what();
  EXPECT_TRUE(contains(set.problems()[0], "(from --set formation.k=2)")) << set.what();
  // AND with the rule it belongs to, the same k is accepted
  EXPECT_EQ(parseAgentConfig("formation: {neighbourhood: k_nearest, k: 2}\n").formation.k, 2);
  EXPECT_EQ(applyOverrides(AgentConfig{}, {"formation.k=2", "formation.neighbourhood=k_nearest"}).formation.k, 2);
}

TEST(AgentConfigApplies, GivenEveryKeyAModeIgnores_ThenEachIsReported) {
  // GIVEN in swa mode with Gabriel: k (k_nearest), anchor.* (anchored; standalone too for the GNSS floor); with the
  // algebraic fit: far_neighbour_weight; with k_nearest: max_edge_factor
  const ConfigError error = expectConfigError([] {
    parseAgentConfig(
        "formation: {k: 4, circle_fit: algebraic, far_neighbour_weight: 0.5}\n"
        "anchor: {gain: 0.3, gnss_min_std_m: 0.1}\n");
  });
  ASSERT_EQ(error.problems().size(), 4u) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "formation.k "), "the k_nearest rule only")) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "formation.far_neighbour_weight"),
                       "applies to the fixed_radius fit only (formation.circle_fit is algebraic)"));
  EXPECT_TRUE(contains(problemAbout(error, "anchor.gain"), "applies to anchored mode only (mode is swa)"));
  EXPECT_TRUE(contains(problemAbout(error, "anchor.gnss_min_std_m"), "the modes that use GNSS"));
  const ConfigError edge =
      expectConfigError([] { parseAgentConfig("formation: {neighbourhood: k_nearest, max_edge_factor: 2}\n"); });
  ASSERT_EQ(edge.problems().size(), 1u) << edge.what();
  EXPECT_TRUE(contains(edge.problems()[0], "formation.max_edge_factor applies to the gabriel rule only"));
  // AND with IMU-bias removal off (window 0) its freeze settings change nothing
  const ConfigError bias =
      expectConfigError([] { parseAgentConfig("focal: {bias_window_s: 0, bias_freeze_hold_s: 3}\n"); });
  ASSERT_EQ(bias.problems().size(), 1u) << bias.what();
  EXPECT_TRUE(contains(bias.problems()[0],
                       "focal.bias_freeze_hold_s applies to IMU-bias removal only "
                       "(focal.bias_window_s is 0)"))
      << bias.what();
  // AND the standalone baseline, which fits no floating frame, refuses the formation keys (k for its mode first),
  // but takes the radius (the monitor scores every run against it) and the GNSS floor
  const ConfigError standalone = expectConfigError([] {
    parseAgentConfig(
        "mode: standalone\nformation: {radius_m: 12, neighbourhood: gabriel, k: 2}\n"
        "anchor: {gnss_min_std_m: 0.1}\n");
  });
  ASSERT_EQ(standalone.problems().size(), 2u) << standalone.what();
  EXPECT_TRUE(contains(problemAbout(standalone, "formation.neighbourhood"),
                       "applies to the modes that fly in formation only (mode is standalone)"));
  EXPECT_TRUE(contains(problemAbout(standalone, "formation.k "), "(mode is standalone); remove it or set mode"));
  EXPECT_EQ(parseAgentConfig("mode: standalone\nformation: {radius_m: 12}\n").formation.radius_m, 12.0);
}

TEST(AgentConfigApplies, GivenALaterSetThatTurnsAFileKeyOff_ThenItIsAccepted) {
  // GIVEN a k_nearest file with k = 2, run once with gabriel by a --set (a study's sweep, swa_launch --compare)
  const ScratchFile file("formation:\n  neighbourhood: k_nearest\n  k: 2\n");
  const AgentConfig c = configTable().load(file.path(), {"formation.neighbourhood=gabriel"});
  // THEN the --set wins and the file's k, now unused, is no error
  EXPECT_EQ(c.formation.neighbourhood, NeighbourhoodRule::kGabriel);
  // AND the same for the whole formation section under a --set of the standalone mode (swa_launch --compare)
  EXPECT_EQ(configTable().load(file.path(), {"mode=standalone"}).mode, Mode::kStandalone);
  // BUT a --set of k is judged against a --set rule, before or after it (a grid point's values come together)
  for (const auto& sets : {std::vector<std::string>{"formation.neighbourhood=gabriel", "formation.k=3"},
                           std::vector<std::string>{"formation.k=3", "formation.neighbourhood=gabriel"}}) {
    const ConfigError error = expectConfigError([&] { configTable().load(file.path(), sets); });
    ASSERT_EQ(error.problems().size(), 1u) << error.what();
    EXPECT_TRUE(contains(error.problems()[0], "(from --set formation.k=3)")) << error.what();
  }
}

TEST(AgentConfigApplies, GivenADumpOfAnOlderVersionThatWroteEveryKey_ThenItIsReadAsADump) {
  // GIVEN a dump that gives k although its rule is gabriel (every dump before issue #24 did)
  const std::string old_dump = "formation:\n  neighbourhood: gabriel\n  k: 4\n";
  // THEN it is refused as a user's file, read as a program's dump, and a --set on top is judged as ever
  EXPECT_EQ(expectConfigError([&] { parseAgentConfig(old_dump); }).problems().size(), 1u);
  EXPECT_EQ(configTable().parseDump(old_dump, "dump").formation.k, 4);
  const ConfigError set = expectConfigError([&] { configTable().parseDump(old_dump, "dump", {"anchor.gain=1"}); });
  ASSERT_EQ(set.problems().size(), 1u) << set.what();
  EXPECT_TRUE(contains(set.problems()[0], "anchor.gain applies to anchored mode only")) << set.what();
}

TEST(AgentConfigApplies, GivenAnUnusedKeyBuiltInCode_WhenDumped_ThenItReadsBackAsAComment) {
  // GIVEN code that set k while the rule is gabriel (no file: nothing to refuse)
  AgentConfig c;
  c.formation.k = 5;
  EXPECT_NO_THROW(validateAgentConfig(c));
  // WHEN dumped and read back
  const std::string yaml = toYaml(c);
  // THEN k is written, commented, and reading the dump is no error (k keeps its default there)
  EXPECT_TRUE(contains(yaml, "  # k: 5")) << yaml;
  EXPECT_EQ(parseAgentConfig(yaml).formation.k, 3);
}

TEST(AgentConfigHelp, GivenTheParameterTable_ThenTheHelpListsEveryKeyWithUnitDefaultAndRange) {
  const std::string help = describeParameters();
  for (const std::string& key : keysOf(toYaml(AgentConfig{}))) {
    EXPECT_TRUE(contains(help, key + " ")) << key;
  }
  // one line per parameter: key, type, unit, default, range, meaning
  std::istringstream lines(help);
  std::string line;
  std::string radius_line;
  while (std::getline(lines, line)) {
    if (line.rfind("formation.radius_m ", 0) == 0) radius_line = line;
  }
  ASSERT_FALSE(radius_line.empty()) << help;
  std::istringstream fields(radius_line);
  std::string key, type, unit, default_value, range_lo, range_hi;
  fields >> key >> type >> unit >> default_value >> range_lo >> range_hi;
  EXPECT_EQ(type, "real");
  EXPECT_EQ(unit, "m");
  EXPECT_EQ(default_value, "10");
  EXPECT_EQ(range_lo + " " + range_hi, "(0, 1000]");
  EXPECT_TRUE(contains(help, "fixed_radius|algebraic"));
  // AND it says which keys a mode ignores
  EXPECT_TRUE(contains(help, "  - formation.k: the k_nearest rule (formation.neighbourhood: k_nearest).")) << help;
  EXPECT_TRUE(contains(help,
                       "focal.bias_freeze_speed_mps, focal.bias_freeze_hold_s: IMU-bias removal "
                       "(focal.bias_window_s not 0)."))
      << help;
}

// ---------------------------------------------------------------------------------------------------------------
// The mission (issue #45): legs in two forms, refused before take-off when they cannot be flown.

TEST(AgentConfigMission, GivenLegsInBothForms_ThenEachIsAVelocityOverATimeThatRunsThroughThePoints) {
  // GIVEN a plan of a velocity leg, then two legs to points at a speed
  const AgentConfig c = parseAgentConfig(
      "mission:\n"
      "  start: time\n"
      "  start_s: 5\n"
      "  legs:\n"
      "    - {velocity_mps: [3, 0], duration_s: 10}\n"
      "    - {to_m: [30, 40], speed_mps: 4}\n"
      "    - {to_m: [0, 0], speed_mps: 5}\n");
  // THEN the point legs start where the plan is (30, 0) and end exactly at their points, at their speeds
  EXPECT_EQ(c.mission.start, MissionStart::kTime);
  EXPECT_EQ(c.mission.start_s, 5.0);
  ASSERT_EQ(c.mission.legs.size(), 3u);
  EXPECT_EQ(c.mission.legs[0].velocity_mps, Vec2(3, 0));
  EXPECT_NEAR(c.mission.legs[1].velocity_mps.norm(), 4.0, 1e-12);
  EXPECT_NEAR(c.mission.legs[1].duration_s, 10.0, 1e-12);  // 40 m north at 4 m/s
  const MissionPlan plan(c.mission.legs);
  EXPECT_NEAR((plan.pathAt(20.0) - Vec2(30, 40)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(plan.endPoint().norm(), 0.0, 1e-9);
  // AND the dump writes them as velocity legs that parse back to the same plan
  expectSameConfig(parseAgentConfig(toYaml(c)), c);
}

TEST(AgentConfigMission, GivenAPlanThatCannotBeFlown_ThenEveryProblemIsNamedBeforeTakeOff) {
  // GIVEN legs that mix forms, leave one half out, name an unknown key, fly too fast, go nowhere, or are not numbers
  const ConfigError error = expectConfigError([] {
    parseAgentConfig(
        "mission:\n"
        "  legs:\n"
        "    - {velocity_mps: [1, 0], duration_s: 5, speed_mps: 2}\n"
        "    - {to_m: [5, 0]}\n"
        "    - {velocity_mps: [1, 0], duration_s: 5, heading: 3}\n"
        "    - {velocity_mps: [6, 0], duration_s: 5}\n"
        "    - {to_m: [0, 0], speed_mps: 2}\n"
        "    - {velocity_mps: [.nan, 0], duration_s: 5}\n"
        "    - {velocity_mps: [1], duration_s: 5}\n");
  });
  // THEN each is refused, naming its leg
  EXPECT_TRUE(contains(problemAbout(error, "mission.legs[0]"), "mixes two forms")) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "mission.legs[1]"), "is incomplete")) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "'heading'"), "mission.legs[2]")) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "mission.legs[5].velocity_mps[0]"), "not a finite number")) << error.what();
  EXPECT_TRUE(contains(problemAbout(error, "mission.legs[6].velocity_mps"), "a list of 2 numbers")) << error.what();
  // AND the rules between legs and the limit are checked once every leg reads: here they do not, so the speed and
  // the leg to nowhere are told when the rest is right
  const ConfigError rules = expectConfigError([] {
    parseAgentConfig(
        "mission:\n"
        "  max_speed_mps: 5\n"
        "  legs:\n"
        "    - {velocity_mps: [6, 0], duration_s: 5}\n"
        "    - {to_m: [30, 0], speed_mps: 2}\n");
  });
  EXPECT_TRUE(contains(problemAbout(rules, "mission.legs[0]"), "above mission.max_speed_mps = 5")) << rules.what();
  EXPECT_TRUE(contains(problemAbout(rules, "mission.legs[1]"), "goes nowhere")) << rules.what();
  // AND start_s without a timed start changes nothing, so it is an error
  const ConfigError start = expectConfigError([] { parseAgentConfig("mission: {start_s: 3}\n"); });
  EXPECT_TRUE(contains(problemAbout(start, "mission.start_s"), "a mission started at a time")) << start.what();
}

}  // namespace
}  // namespace swa::agent
