// A golden time series of one seeded scenario: any numeric change in the agent, the simulator or the metrics shows
// up here, in review, as a changed CSV. Regenerate deliberately with SWA_UPDATE_GOLDEN=1 and commit the diff.

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "closed_loop_support.h"

namespace swa::batch {
namespace {

const std::string kGolden = std::string(SWA_SOURCE_DIR) + "/tests/closedloop/golden/dropout_4_seed_7_30s.csv";

std::vector<std::vector<std::string>> readCsv(std::istream& in) {
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(ClosedLoopGolden, FourUavsSeed7MatchesTheGoldenTimeSeries) {
  // GIVEN the 4-UAV dropout scenario, seed 7, 30 s
  const RunResult r = runClosedLoop(testing::shipped("dropout_4", {"seed=7", "duration_s=30"}));
  std::ostringstream csv;
  csv << monitor::csvHeader() << "\n";
  for (const auto& row : r.series) csv << monitor::formatCsvRow(row) << "\n";
  if (std::getenv("SWA_UPDATE_GOLDEN") != nullptr) {
    std::ofstream(kGolden) << csv.str();
    GTEST_SKIP() << "golden file rewritten: " << kGolden;
  }
  // WHEN compared with the committed golden CSV
  std::ifstream golden_file(kGolden);
  ASSERT_TRUE(golden_file) << "missing " << kGolden;
  std::istringstream produced(csv.str());
  const auto expected = readCsv(golden_file);
  const auto actual = readCsv(produced);
  // THEN every cell matches: text for the header, 1e-9 relative (1e-12 absolute) for numbers, which allows for a
  // different libm but not for a changed algorithm
  ASSERT_EQ(actual.size(), expected.size());
  ASSERT_EQ(actual.front(), expected.front());
  int mismatches = 0;
  for (std::size_t i = 1; i < expected.size(); ++i) {
    ASSERT_EQ(actual[i].size(), expected[i].size()) << "row " << i;
    for (std::size_t j = 0; j < expected[i].size(); ++j) {
      const double e = std::strtod(expected[i][j].c_str(), nullptr);
      const double a = std::strtod(actual[i][j].c_str(), nullptr);
      const bool both_nan = std::isnan(e) && std::isnan(a);
      if (!both_nan && !(std::abs(a - e) <= 1e-12 + 1e-9 * std::abs(e))) {
        if (++mismatches <= 5) ADD_FAILURE() << "row " << i << " column " << expected[0][j] << ": " << a << " vs " << e;
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace swa::batch
