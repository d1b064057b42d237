// The loop-latency statistics of swa_sim (sim/node/latency_stats.h): the log-spaced histogram's quantiles against
// exact order statistics, and the per-command bookkeeping (latency, late, missing, duplicate, unmatched answers).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "latency_stats.h"

namespace swa::sim_node {
namespace {

constexpr WallNs kUs = 1'000;
constexpr WallNs kMs = 1'000'000;

// The order statistic of rank ceil(q n) (rank 1 for q = 0), as LogHistogram::quantileNs defines it.
double exactQuantile(std::vector<WallNs> v, double q) {
  std::sort(v.begin(), v.end());
  const auto rank = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))));
  return static_cast<double>(v[rank - 1]);
}

// ---- LogHistogram ---------------------------------------------------------------------------------------------------

TEST(LogHistogram, EmptyHistogramHasNoStatistics) {
  const LogHistogram h;
  EXPECT_EQ(h.count(), 0u);
  EXPECT_TRUE(std::isnan(h.quantileNs(0.5)));
  EXPECT_TRUE(std::isnan(h.maxNs()));
  EXPECT_TRUE(std::isnan(h.meanNs()));
}

TEST(LogHistogram, ResolutionIsAboutOnePercent) { EXPECT_NEAR(LogHistogram::relativeResolution(), 0.01158, 1e-4); }

TEST(LogHistogram, QuantilesAreWithinTheStatedResolutionOfTheExactOrderStatistics) {
  // GIVEN 20000 latencies spread log-uniformly over 20 us .. 50 ms (seeded)
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(std::log10(20e3), std::log10(50e6));
  std::vector<WallNs> values;
  LogHistogram h;
  for (int i = 0; i < 20000; ++i) {
    const auto v = static_cast<WallNs>(std::pow(10.0, exponent(rng)));
    values.push_back(v);
    h.add(v);
  }
  // THEN every quantile is within the resolution, and the extremes and the mean are exact
  const double tol = LogHistogram::relativeResolution();
  for (const double q : {0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999}) {
    const double exact = exactQuantile(values, q);
    EXPECT_NEAR(h.quantileNs(q), exact, tol * exact * 1.0001) << "q = " << q;
  }
  EXPECT_EQ(h.quantileNs(0.0), exactQuantile(values, 0.0));
  EXPECT_EQ(h.quantileNs(1.0), static_cast<double>(*std::max_element(values.begin(), values.end())));
  EXPECT_EQ(h.maxNs(), static_cast<double>(*std::max_element(values.begin(), values.end())));
  EXPECT_EQ(h.minNs(), static_cast<double>(*std::min_element(values.begin(), values.end())));
  double sum = 0.0;
  for (const WallNs v : values) sum += static_cast<double>(v);
  EXPECT_NEAR(h.meanNs(), sum / static_cast<double>(values.size()), 1e-6 * sum / static_cast<double>(values.size()));
}

TEST(LogHistogram, ASingleValueIsReportedExactly) {
  LogHistogram h;
  h.add(93 * kUs + 417);
  EXPECT_EQ(h.quantileNs(0.5), 93'417.0);
  EXPECT_EQ(h.quantileNs(0.99), 93'417.0);
}

TEST(LogHistogram, ValuesOutsideTheRangeKeepExactExtremes) {
  // GIVEN values below 1 us (and a negative one: a clock step, counted as 0) and above 100 s
  LogHistogram h;
  h.add(-5);
  h.add(300);
  h.add(500 * kUs);
  h.add(200'000 * kMs);
  EXPECT_EQ(h.count(), 4u);
  EXPECT_EQ(h.minNs(), 0.0);
  EXPECT_EQ(h.maxNs(), 200'000.0 * kMs);
  EXPECT_EQ(h.quantileNs(0.5), 0.0);  // rank 2 (300 ns) is in the underflow bin, which reports the smallest value
  EXPECT_EQ(h.quantileNs(0.99), 200'000.0 * kMs);
  EXPECT_NEAR(h.quantileNs(0.75), 500.0 * kUs, LogHistogram::relativeResolution() * 500.0 * kUs);
}

TEST(LogHistogram, MergeEqualsAddingEverythingToOne) {
  LogHistogram a, b, all;
  for (int i = 1; i <= 100; ++i) {
    (i % 3 ? a : b).add(i * 37 * kUs);
    all.add(i * 37 * kUs);
  }
  a.merge(b);
  EXPECT_EQ(a.count(), all.count());
  for (const double q : {0.0, 0.5, 0.9, 0.99, 1.0}) EXPECT_EQ(a.quantileNs(q), all.quantileNs(q)) << q;
  EXPECT_EQ(a.meanNs(), all.meanNs());
}

// ---- CommandLatencyTracker ------------------------------------------------------------------------------------------

constexpr std::int64_t kStepNs = 10 * kMs;  // sim time of one 100 Hz step

TEST(CommandLatencyTracker, AnswersBeforeTheirDeadlineAreOnTimeAfterItLate) {
  // GIVEN two UAVs, samples published at wall 0 with their deadline one step later
  CommandLatencyTracker t(2);
  t.published(0, 1, 0, 0, 10 * kMs);
  t.published(1, 1, 0, 50 * kUs, 10 * kMs + 50 * kUs);
  // WHEN UAV 0 answers after 90 us, the simulator takes the next step on time, and UAV 1 answers after 12 ms
  t.answered(0, 1, 0, 90 * kUs);
  t.stepTaken(10 * kMs);
  t.answered(1, 1, 0, 50 * kUs + 12 * kMs);
  t.finish(20 * kMs);
  // THEN both latencies are recorded, one command is late, none missing
  const LatencyReport r = t.report();
  EXPECT_EQ(r.answered, 2u);
  EXPECT_EQ(r.published, 2u);
  EXPECT_EQ(r.late, 1u);
  EXPECT_EQ(r.missing, 0u);
  EXPECT_DOUBLE_EQ(r.lateFraction(), 0.5);
  EXPECT_EQ(r.max_us, 12'000.0);
  EXPECT_EQ(r.p50_us, 90.0);  // rank 1 of 2: the smallest, exact
  EXPECT_DOUBLE_EQ(r.mean_us, (90.0 + 12'000.0) / 2.0);
}

TEST(CommandLatencyTracker, AnAnswerExactlyAtTheDeadlineIsOnTime) {
  CommandLatencyTracker t(1);
  t.published(0, 1, 0, 0, 10 * kMs);
  t.stepTaken(10 * kMs);
  t.answered(0, 1, 0, 10 * kMs);
  EXPECT_EQ(t.report().late, 0u);
  t.published(0, 2, kStepNs, 10 * kMs, 20 * kMs);
  t.stepTaken(20 * kMs);
  t.answered(0, 2, kStepNs, 20 * kMs + 1);
  EXPECT_EQ(t.report().late, 1u);
}

TEST(CommandLatencyTracker, AnAnswerIsLateOnlyWhenItMissedTheStepItAnswers) {
  // GIVEN two UAVs' samples due at 10 ms, and a simulator that is itself late: it takes the next step at 18 ms
  CommandLatencyTracker t(2);
  t.published(0, 1, 0, 0, 10 * kMs);
  t.published(1, 1, 0, 0, 10 * kMs);
  // WHEN UAV 0 answers at 15 ms, past the due time but before the step (the simulator still applies it) ...
  t.answered(0, 1, 0, 15 * kMs);
  EXPECT_EQ(t.report().late, 0u);
  // ... and UAV 1 at 19 ms, after the step took the commands it had
  t.stepTaken(18 * kMs);
  t.answered(1, 1, 0, 19 * kMs);
  // THEN only UAV 1's answer is late; both latencies are recorded as they were
  const LatencyReport r = t.report();
  EXPECT_EQ(r.late, 1u);
  EXPECT_EQ(r.answered, 2u);
  EXPECT_EQ(r.max_us, 19'000.0);
  // THEN an answer received at 17 ms, before the step took its commands at 18 ms, is in time even when it is judged
  // after the step (queued just after the last drain)
  CommandLatencyTracker u(1);
  u.published(0, 1, 0, 0, 10 * kMs);
  u.stepTaken(18 * kMs);
  u.answered(0, 1, 0, 17 * kMs);
  EXPECT_EQ(u.report().late, 0u);
  // THEN when the step's last drain began before the due time (the simulator on time), the due time stays the
  // deadline: an answer at 29.5 ms is in time, one at 31 ms late
  t.published(0, 2, kStepNs, 20 * kMs, 30 * kMs);
  t.stepTaken(29 * kMs);
  t.answered(0, 2, kStepNs, 29 * kMs + 500 * kUs);
  EXPECT_EQ(t.report().late, 1u);
  t.published(1, 2, kStepNs, 20 * kMs, 30 * kMs);
  t.stepTaken(29 * kMs);
  t.answered(1, 2, kStepNs, 31 * kMs);
  EXPECT_EQ(t.report().late, 2u);
}

TEST(CommandLatencyTracker, NewestAnsweredOnceEveryUavAnsweredItsNewestSample) {
  CommandLatencyTracker t(2);
  EXPECT_TRUE(t.newestAnswered());  // nothing published
  t.published(0, 1, 0, 0, 10 * kMs);
  t.published(1, 1, 0, 0, 10 * kMs);
  t.answered(0, 1, 0, 1 * kMs);
  EXPECT_FALSE(t.newestAnswered());
  t.answered(1, 1, 0, 2 * kMs);
  EXPECT_TRUE(t.newestAnswered());
  t.published(0, 2, kStepNs, 10 * kMs, 20 * kMs);  // an older sample answered does not count for the newer one
  EXPECT_FALSE(t.newestAnswered());
}

TEST(CommandLatencyTracker, ASampleWhoseSuccessorWasPublishedIsJudgedAgainstItsOwnDeadline) {
  // GIVEN sample 1 due at 10 ms, then sample 2 published without a stepTaken() in between
  CommandLatencyTracker t(1);
  t.published(0, 1, 0, 0, 10 * kMs);
  t.published(0, 2, kStepNs, 10 * kMs, 20 * kMs);
  // WHEN sample 1 is answered at 12 ms, sample 2 at 15 ms (its step not taken yet)
  t.answered(0, 1, 0, 12 * kMs);
  t.answered(0, 2, kStepNs, 15 * kMs);
  // THEN sample 1 missed its step (the next sample was out); sample 2 is in time
  EXPECT_EQ(t.report().late, 1u);
}

TEST(CommandLatencyTracker, DuplicateAndForeignAnswersAreCountedApartAndNotTimed) {
  CommandLatencyTracker t(2, 8);
  t.published(0, 5, 4 * kStepNs, 0, 10 * kMs);
  t.answered(0, 5, 4 * kStepNs, 100 * kUs);
  t.answered(0, 5, 4 * kStepNs, 200 * kUs);  // the same answer again
  t.answered(0, 6, 5 * kStepNs, 300 * kUs);  // a sample never published
  t.answered(0, 5, 9 * kStepNs, 300 * kUs);  // right seq, wrong stamp: another run's history
  t.answered(7, 5, 4 * kStepNs, 300 * kUs);  // no such UAV
  t.answered(1, 5, 4 * kStepNs, 300 * kUs);  // UAV 1 was sent nothing
  const LatencyReport r = t.report();
  EXPECT_EQ(r.answered, 1u);
  EXPECT_EQ(r.duplicates, 1u);
  EXPECT_EQ(r.unmatched, 4u);
  EXPECT_EQ(r.max_us, 100.0);
}

TEST(CommandLatencyTracker, ASampleEvictedUnansweredIsMissingAndItsLateAnswerUnmatched) {
  // GIVEN a window of 4 samples and a UAV that never answers sample 1
  CommandLatencyTracker t(1, 4);
  for (std::uint32_t seq = 1; seq <= 4; ++seq) {
    const auto wall = static_cast<WallNs>(seq) * 10 * kMs;
    t.published(0, seq, seq * kStepNs, wall, wall + 10 * kMs);
    if (seq != 1) t.answered(0, seq, seq * kStepNs, wall + 100 * kUs);
  }
  EXPECT_EQ(t.report().missing, 0u);
  // WHEN sample 5 takes sample 1's slot
  t.published(0, 5, 5 * kStepNs, 50 * kMs, 60 * kMs);
  // THEN sample 1 is missing, and an answer to it that still turns up is unmatched, not timed
  EXPECT_EQ(t.report().missing, 1u);
  t.answered(0, 1, 1 * kStepNs, 55 * kMs);
  EXPECT_EQ(t.report().unmatched, 1u);
  EXPECT_EQ(t.report().answered, 3u);
}

TEST(CommandLatencyTracker, FinishCountsOverdueSamplesAsMissingAndDropsThoseStillInTime) {
  // GIVEN samples at 0, 10, 20 ms (deadlines 10, 20, 30 ms), only the first answered
  CommandLatencyTracker t(1);
  for (std::uint32_t seq = 1; seq <= 3; ++seq) {
    const WallNs wall = (seq - 1) * 10 * kMs;
    t.published(0, seq, (seq - 1) * kStepNs, wall, wall + 10 * kMs);
  }
  t.answered(0, 1, 0, 1 * kMs);
  // WHEN the books close at 25 ms
  t.finish(25 * kMs);
  // THEN sample 2 (due at 20 ms) is missing; sample 3 (due at 30 ms) is not judged
  const LatencyReport r = t.report();
  EXPECT_EQ(r.missing, 1u);
  EXPECT_EQ(r.published, 2u);
  EXPECT_DOUBLE_EQ(r.missingFraction(), 0.5);
  // THEN finish() is idempotent
  t.finish(100 * kMs);
  EXPECT_EQ(t.report().missing, 1u);
}

TEST(CommandLatencyTracker, WithoutDeadlinesNothingIsLateAndUnansweredSamplesAreMissingAtTheEnd) {
  // GIVEN lockstep: no deadlines; an answer after a full second is slow, not late
  CommandLatencyTracker t(2);
  t.published(0, 1, 0, 0, std::nullopt);
  t.published(1, 1, 0, 0, std::nullopt);
  t.answered(0, 1, 0, 1'000 * kMs);
  t.finish(2'000 * kMs);
  const LatencyReport r = t.report();
  EXPECT_EQ(r.late, 0u);
  EXPECT_EQ(r.missing, 1u);  // UAV 1 never answered (a dead agent)
  EXPECT_EQ(r.max_us, 1e6);
}

TEST(CommandLatencyTracker, EmptyRunReportsZerosAndNaNLatencies) {
  CommandLatencyTracker t(3);
  t.finish(0);
  const LatencyReport r = t.report();
  EXPECT_EQ(r.published, 0u);
  EXPECT_EQ(r.lateFraction(), 0.0);
  EXPECT_TRUE(std::isnan(r.p50_us));
}

}  // namespace
}  // namespace swa::sim_node
