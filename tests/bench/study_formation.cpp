// Formation-quality study (issue #10): the closed loop over seeds for every swarm size in a range, one row per size
// and neighbourhood rule, the metrics of DESIGN §5 side by side. A table-printing program, not a test: the
// closed-loop statistics assert the targets on fewer seeds (tests/closedloop/formation_statistics.cpp).
//
//   study_formation [--seeds 20] [--jobs 2] [--sizes 3-16] [--fov 360] [--duration 600] [--rules gabriel,k3]
//                   [--scenario FILE] [--set key=value]...
//
// --sizes takes ranges and lists (3-16, or 3,8,16,32-33); --fov a list of fields of view in degrees (mps.fov_deg,
// which the agents also take as theirs: below 360 they turn to face one way, issue #26). For the agents'
// constant-heading behaviour under a limited field of view, add --set agent.sensor.fov_deg=360.
//
// It is swa_batch's study (deploy/programs/batch/study_runner.h) with its own table: the sweep mps.fov_deg x uav_count,
// the rules as the study's variants (swa_batch --variant), the same runs and seeds; only the table (d_NB at 120 s, the
// split runs, the worst separation) is this program's. A --set of a key a rule sets is refused.
//
// Rules (each spelled out, so the table does not change meaning with the defaults): gabriel = Gabriel + weighted fit
// (0.2) + IMU-bias removal (30 s); gabriel_nobias = the same without bias removal; gabriel_nocap = without the
// edge-length cap (Gabriel's test alone); k3 / k2 = k nearest with the
// unweighted fixed-radius fit and no bias removal (k3 was the default before issue #10). Other parameters keep the
// defaults of the scenario file and the agent.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "batch_runner.h"
#include "study_runner.h"

namespace {

using swa::batch::RunResult;

const std::map<std::string, std::vector<std::string>> kRules = {
    {"gabriel",
     {"agent.formation.neighbourhood=gabriel", "agent.formation.far_neighbour_weight=0.2",
      "agent.focal.bias_window_s=30"}},
    {"gabriel_nobias",
     {"agent.formation.neighbourhood=gabriel", "agent.formation.far_neighbour_weight=0.2",
      "agent.focal.bias_window_s=0"}},
    {"gabriel_nocap",
     {"agent.formation.neighbourhood=gabriel", "agent.formation.far_neighbour_weight=0.2",
      "agent.focal.bias_window_s=30", "agent.formation.max_edge_factor=100"}},
    {"k3",
     {"agent.formation.neighbourhood=k_nearest", "agent.formation.k=3", "agent.formation.far_neighbour_weight=1",
      "agent.focal.bias_window_s=0"}},
    {"k2",
     {"agent.formation.neighbourhood=k_nearest", "agent.formation.k=2", "agent.formation.far_neighbour_weight=1",
      "agent.focal.bias_window_s=0"}},
};

struct Options {
  int seeds = 20;
  int jobs = 2;
  std::vector<int> sizes;
  std::vector<double> fovs = {360.0};
  double duration_s = 600.0;
  std::vector<std::string> rules = {"gabriel", "k3"};
  std::string scenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_8.yaml";
  std::vector<std::string> sets;
};

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "study_formation: %s\nusage: study_formation [--seeds N] [--jobs J] [--sizes A-B,C,...] [--fov D1,D2]\n"
               "         [--duration S] [--rules r1,r2] [--scenario FILE] [--set key=value]...\nrules:",
               why);
  for (const auto& [name, sets] : kRules) std::fprintf(stderr, " %s", name.c_str());
  std::fprintf(stderr, "\n");
  std::exit(2);
}

std::vector<std::string> splitCommas(const std::string& v) {
  std::vector<std::string> out;
  for (std::size_t s = 0, e; s <= v.size(); s = e + 1) {
    e = std::min(v.find(',', s), v.size());
    out.push_back(v.substr(s, e - s));
  }
  return out;
}

// "3-16", "8", "3,8,16-18": every size, in the order given; false for a malformed part or a size below 2.
bool parseSizes(const std::string& v, std::vector<int>& out) {
  for (const std::string& part : splitCommas(v)) {
    int from = 0, to = 0;
    char tail = 0;
    if (std::sscanf(part.c_str(), "%d-%d%c", &from, &to, &tail) == 2) {
      // a range
    } else if (std::sscanf(part.c_str(), "%d%c", &from, &tail) == 1) {
      to = from;
    } else {
      return false;
    }
    if (from < 2 || to < from) return false;
    for (int n = from; n <= to; ++n) out.push_back(n);
  }
  return !out.empty();
}

Options parse(int argc, char** argv) {
  Options o;
  bool fov_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help") usage("formation quality over swarm sizes and rules");
    if (i + 1 >= argc) usage(("missing value after " + a).c_str());
    const std::string v = argv[++i];
    if (a == "--seeds") {
      o.seeds = std::atoi(v.c_str());
    } else if (a == "--jobs") {
      o.jobs = std::atoi(v.c_str());
    } else if (a == "--duration") {
      o.duration_s = std::atof(v.c_str());
    } else if (a == "--sizes") {
      o.sizes.clear();
      if (!parseSizes(v, o.sizes)) usage(("bad --sizes " + v + " (e.g. 3-16 or 3,8,16; sizes >= 2)").c_str());
    } else if (a == "--fov") {
      fov_given = true;
      o.fovs.clear();
      for (const std::string& f : splitCommas(v)) {
        char* end = nullptr;
        const double d = std::strtod(f.c_str(), &end);
        if (end == f.c_str() || *end != '\0' || !(d > 0.0 && d <= 360.0)) usage(("bad --fov " + f).c_str());
        o.fovs.push_back(d);
      }
    } else if (a == "--rules") {
      o.rules = splitCommas(v);
    } else if (a == "--scenario") {
      o.scenario = v;
    } else if (a == "--set") {
      o.sets.push_back(v);
    } else {
      usage(("unknown option " + a).c_str());
    }
  }
  for (const std::string& r : o.rules)
    if (kRules.count(r) == 0) usage(("unknown rule " + r).c_str());
  // --set mps.fov_deg=D is one field of view: the sweep's, so that the table's FOV column says which.
  for (auto it = o.sets.begin(); it != o.sets.end();) {
    if (it->rfind("mps.fov_deg=", 0) != 0) {
      ++it;
      continue;
    }
    if (fov_given) usage("the field of view is given by --fov and by --set mps.fov_deg: give it once");
    char* end = nullptr;
    const std::string value = it->substr(std::string("mps.fov_deg=").size());
    const double d = std::strtod(value.c_str(), &end);
    if (end == value.c_str() || *end != '\0' || !(d > 0.0 && d <= 360.0)) usage(("bad " + *it).c_str());
    o.fovs = {d};
    it = o.sets.erase(it);
  }
  if (o.sizes.empty()) {
    for (int n = 3; n <= 16; ++n) o.sizes.push_back(n);
  }
  if (o.seeds < 1 || o.jobs < 1 || !(o.duration_s > 120.0)) usage("need seeds >= 1, jobs >= 1, duration > 120 s");
  return o;
}

struct Column {
  double sum = 0.0, sq = 0.0;
  int n = 0;
  void add(double v) {
    if (!std::isfinite(v)) return;
    sum += v;
    sq += v * v;
    ++n;
  }
  double mean() const { return n > 0 ? sum / n : std::numeric_limits<double>::quiet_NaN(); }
  double stdev() const { return n > 1 ? std::sqrt(std::max(0.0, (sq - sum * sum / n) / (n - 1))) : 0.0; }
};

// The study: fov x size x rule (the variants, last: fastest), every cell run for the same seeds.
swa::batch::BatchOptions studyOptions(const Options& o) {
  swa::batch::BatchOptions b;
  b.scenario_path = o.scenario;
  b.overrides = {"duration_s=" + std::to_string(o.duration_s)};
  b.overrides.insert(b.overrides.end(), o.sets.begin(), o.sets.end());
  std::string fovs, sizes;
  for (const double f : o.fovs) fovs += (fovs.empty() ? "" : ",") + std::to_string(f);
  for (const int n : o.sizes) sizes += (sizes.empty() ? "" : ",") + std::to_string(n);
  b.sweeps = {"mps.fov_deg=" + fovs, "uav_count=" + sizes};
  for (const std::string& rule : o.rules) {
    std::string variant = rule + ":";
    for (const std::string& set : kRules.at(rule)) variant += (variant.back() == ':' ? "" : ",") + set;
    b.variants.push_back(variant);
  }
  b.seeds = o.seeds;
  b.seeds_given = true;
  return b;
}

// One row of the table: a grid point's runs.
struct Cell {
  Column d120, dend, edge, drift, disp, anees, in_band;
  int split = 0, collided = 0, runs = 0;
  std::uint64_t collisions = 0;
  double worst = std::numeric_limits<double>::infinity();
  void add(const RunResult& run) {
    const auto& s = run.summary;
    d120.add(swa::batch::meanNeighbourDistanceAt(run, 120.0));
    dend.add(s.mean_neighbor_distance_m);
    edge.add(s.edge_length_m);
    drift.add(s.drift_velocity_windows_mps);
    disp.add(s.centroid_displacement_m);
    anees.add(s.anees_position);
    in_band.add(s.anees_position_in_band);
    split += s.groups > 1 ? 1 : 0;
    collisions += s.collisions;
    collided += s.collisions > 0 ? 1 : 0;
    worst = std::min(worst, s.min_separation_m);
    ++runs;
  }
};

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  // Every cell's scenario before the first run: a --set one rule refuses stops the study now, not an hour in.
  swa::batch::PreparedStudy study;
  try {
    study = swa::batch::prepareStudy(studyOptions(o), swa::study::StudySection{});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "study_formation: %s\n", e.what());
    return 2;
  }
  std::printf("study_formation: %s, %d seeds, %.0f s, GNSS lost as in the scenario; extra:", o.scenario.c_str(),
              o.seeds, o.duration_s);
  for (const std::string& s : o.sets) std::printf(" %s", s.c_str());
  std::printf(
      "\n\n| N | FOV | rule | d_NB 120 s | d_NB end | edge end | runs split | collisions (runs) | "
      "worst min sep | "
      "drift, 60 s windows | centroid disp. | ANEES pos (in band) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  // A row is printed once its runs and every earlier row's are in.
  std::vector<Cell> cells(swa::study::pointCount(study.record.plan));
  std::size_t next_row = 0;
  const std::atomic<bool> never{false};
  swa::batch::runEach(
      swa::batch::runScenarios(study), o.jobs,
      [&](std::size_t k, RunResult&& run) {
        cells[study.runs[k].point].add(run);
        for (; next_row < cells.size() && cells[next_row].runs == o.seeds; ++next_row) {
          const Cell& c = cells[next_row];
          const std::vector<std::string> v = swa::study::pointValues(study.record.plan, next_row);
          std::printf(
              "| %s | %.0f° | %s | %.3f ± %.2f | %.3f ± %.2f | %.2f | %d/%d | %llu (%d) | %.2f | %.3f | "
              "%.1f | %.2f (%.0f %%) |\n",
              v[1].c_str(), std::stod(v[0]), v[2].c_str(), c.d120.mean(), c.d120.stdev(), c.dend.mean(), c.dend.stdev(),
              c.edge.mean(), c.split, o.seeds, static_cast<unsigned long long>(c.collisions), c.collided, c.worst,
              c.drift.mean(), c.disp.mean(), c.anees.mean(), 100.0 * c.in_band.mean());
          std::fflush(stdout);
        }
      },
      never);
  return 0;
}
