// The statistics of rbcflow study (apps/study_analysis.h) on synthetic diagnostics whose
// answers are known: the steady window, the mean, the batch-means standard error of white
// noise, the drift of a linear trend and the pressure-gradient fluctuation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>

#include "apps/study_analysis.h"
#include "io/csv.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

// diagnostics.csv with `rows` steps of dt = 0.01: effective viscosity mu(t), pressure gradient
// along z g(t); the other columns are not read by steady_average.
fs::path write_diagnostics(const std::string& name, int rows, const std::function<double(int)>& mu,
                           const std::function<double(int)>& g) {
  const fs::path path = fs::temp_directory_path() / ("rbcflow_test_study_analysis_" + name + ".csv");
  fs::remove(path);
  CsvWriter csv(path, {"step", "time", "pressure_gradient_x", "pressure_gradient_y", "pressure_gradient_z",
                       "effective_viscosity"});
  for (int i = 1; i <= rows; ++i) {
    csv.write({std::to_string(i), csv_number(0.01 * i), "0", "0", csv_number(g(i)), csv_number(mu(i))});
  }
  return path;
}

}  // namespace

TEST(StudyAnalysis, AveragesTheSteadyPartOfAConstantSeries) {
  const fs::path csv = write_diagnostics("constant", 100, [](int) { return 1.25; }, [](int) { return -40.0; });
  const cli::SteadyAverage a = cli::steady_average(csv, 2, 0.5);
  EXPECT_EQ(a.rows, 51);  // t = 0.50 .. 1.00
  EXPECT_DOUBLE_EQ(a.from_time, 0.5);
  EXPECT_DOUBLE_EQ(a.to_time, 1.0);
  EXPECT_DOUBLE_EQ(a.mean, 1.25);
  EXPECT_EQ(a.standard_error, 0.0);
  EXPECT_EQ(a.drift, 0.0);
  EXPECT_EQ(a.pressure_gradient_fluctuation, 0.0);
}

// White noise of standard deviation s: the batch means estimate s / sqrt(n). With 10 batches
// the estimate has 9 degrees of freedom, so its relative spread is about 1 / sqrt(18) = 24%;
// the bounds below are beyond 3 of those spreads on each side.
TEST(StudyAnalysis, BatchMeansErrorOfWhiteNoise) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<double> mu(2001);
  for (double& m : mu) m = 1.3 + noise(rng);
  const fs::path csv = write_diagnostics("noise", 2000, [&](int i) { return mu[i]; }, [](int) { return -40.0; });
  const cli::SteadyAverage a = cli::steady_average(csv, 2, 0.5);
  ASSERT_EQ(a.rows, 1001);
  const double expected = 0.02 / std::sqrt(1001.0);
  EXPECT_NEAR(a.mean, 1.3, 4 * expected);
  EXPECT_GT(a.standard_error, 0.3 * expected);
  EXPECT_LT(a.standard_error, 1.8 * expected);
  EXPECT_LT(std::abs(a.drift), 8 * expected / 1.3);  // two halves: difference spread 2 s / sqrt(n)
}

// mu = 1 + 0.2 t over the window [0.5, 1]: the second half's mean exceeds the first half's
// by 0.2 x (half the window) exactly, relative to the mean 1.15.
TEST(StudyAnalysis, DriftOfALinearTrend) {
  const fs::path csv =
      write_diagnostics("trend", 100, [](int i) { return 1.0 + 0.2 * (0.01 * i); }, [](int) { return -40.0; });
  const cli::SteadyAverage a = cli::steady_average(csv, 2, 0.5);
  ASSERT_EQ(a.rows, 51);  // halves of 25 rows: t = 0.50..0.74 and 0.76..1.00
  EXPECT_NEAR(a.mean, 1.15, 1e-12);
  EXPECT_NEAR(a.drift, 0.2 * 0.26 / 1.15, 1e-12);
}

TEST(StudyAnalysis, PressureGradientFluctuation) {
  // g = -40 (1 + 0.01 sin): (max - min) / |mean| over the window.
  const fs::path csv = write_diagnostics("gradient", 400, [](int) { return 1.2; },
                                         [](int i) { return -40.0 * (1.0 + 0.01 * std::sin(0.1 * i)); });
  const cli::SteadyAverage a = cli::steady_average(csv, 2, 0.5);
  EXPECT_NEAR(a.pressure_gradient_fluctuation, 0.02, 2e-4);  // sampled sine: extremes within 1%
}

TEST(StudyAnalysis, RefusesAFileWithoutEffectiveViscosity) {
  // A case without a straight tube leaves the column empty.
  const fs::path csv = fs::temp_directory_path() / "rbcflow_test_study_analysis_no_tube.csv";
  {
    CsvWriter empty(csv, {"step", "time", "pressure_gradient_x", "pressure_gradient_y", "pressure_gradient_z",
                          "effective_viscosity"});
    empty.write({"1", "0.01", "0", "0", "-1", ""});
  }
  EXPECT_THROW(cli::steady_average(csv, 2, 0.5), std::runtime_error);
}

// The measured tube columns: their means (and the largest area strain) over the same steady
// rows; empty where the file has no such column (a run written before them).
TEST(StudyAnalysis, AveragesTheMeasuredTubeColumns) {
  const fs::path path = fs::temp_directory_path() / "rbcflow_test_study_analysis_measured.csv";
  fs::remove(path);
  {
    CsvWriter csv(path, {"step", "time", "pressure_gradient_x", "pressure_gradient_y", "pressure_gradient_z",
                         "effective_viscosity", "tube_velocity", "discharge_hematocrit", "max_area_strain",
                         "cell_free_layer", "min_wall_gap"});
    for (int i = 1; i <= 100; ++i) {
      // Linear in i: the mean over i = 50..100 is the value at i = 75.
      csv.write({std::to_string(i), csv_number(0.01 * i), "0", "0", "-40", "1.5", csv_number(2.0 + 0.01 * i),
                 csv_number(0.25 + 0.001 * i), csv_number(i % 7 == 0 ? 0.03 : 0.01), "0.5",
                 csv_number(i == 20 ? 0.01 : i == 60 ? 0.05 : 0.2)});
    }
  }
  const cli::SteadyAverage a = cli::steady_average(path, 2, 0.5);
  ASSERT_TRUE(a.tube_velocity && a.discharge_hematocrit && a.max_area_strain && a.cell_free_layer);
  EXPECT_EQ(*a.cell_free_layer, 0.5);
  ASSERT_TRUE(a.min_wall_gap);
  EXPECT_EQ(*a.min_wall_gap, 0.05);  // the smallest in the steady rows (0.01 at i = 20 is before them)
  EXPECT_NEAR(*a.tube_velocity, 2.75, 1e-12);
  EXPECT_NEAR(*a.discharge_hematocrit, 0.325, 1e-12);
  EXPECT_EQ(*a.max_area_strain, 0.03);
  EXPECT_EQ(a.pressure_gradient, -40.0);
  fs::remove(path);

  const fs::path old = write_diagnostics("without_measured", 10, [](int) { return 1.25; }, [](int) { return -40.0; });
  const cli::SteadyAverage b = cli::steady_average(old, 2, 0.5);
  EXPECT_FALSE(b.tube_velocity || b.discharge_hematocrit || b.max_area_strain || b.cell_free_layer || b.min_wall_gap);
  fs::remove(old);
}

// A run restarted at half the time step: 50 rows of dt = 0.02 over (0, 1] with mu = 1, then
// 100 rows of dt = 0.01 over (1, 2] with mu = 2. From t = 0.5 each row holds over its step: mu
// = 1 over (0.48, 1] (the row at t = 0.5 covers its step) and 2 over (1, 2], a time mean of
// (0.52 + 2) / 1.52; the mean of the rows would be (26 + 200) / 126 = 1.79.
TEST(StudyAnalysis, SteadyMeansAreTimeMeans) {
  const fs::path path = fs::temp_directory_path() / "rbcflow_test_study_analysis_two_steps.csv";
  fs::remove(path);
  {
    CsvWriter csv(path, {"step", "time", "pressure_gradient_x", "pressure_gradient_y", "pressure_gradient_z",
                         "effective_viscosity", "tube_velocity"});
    for (int i = 1; i <= 150; ++i) {
      const bool fine = i > 50;
      const double t = fine ? 1.0 + 0.01 * (i - 50) : 0.02 * i;
      csv.write({std::to_string(i), csv_number(t), "0", "0", fine ? "-20" : "-10", fine ? "2" : "1", fine ? "4" : "3"});
    }
  }
  const cli::SteadyAverage a = cli::steady_average(path, 2, 0.25);
  EXPECT_EQ(a.rows, 126);
  EXPECT_NEAR(a.mean, 2.52 / 1.52, 1e-12);
  EXPECT_NEAR(a.pressure_gradient, -(0.52 * 10 + 20) / 1.52, 1e-12);
  ASSERT_TRUE(a.tube_velocity);
  EXPECT_NEAR(*a.tube_velocity, (0.52 * 3 + 4) / 1.52, 1e-12);
  fs::remove(path);
}

// A bifurcation's branches.csv written by hand: over 100 steps the parent carries 2.0, alpha
// 1.25 and beta 0.75; every 4th step a cell passes the parent, and of those, two in three go
// to alpha. Over the second half (t >= 0.5: steps 50..100) the blood fraction is 0.625, and
// the cells' fraction the counted passages' with its binomial error.
TEST(StudyAnalysis, PhaseSeparationPointFromBranches) {
  const fs::path path = fs::temp_directory_path() / "rbcflow_test_study_analysis_branches.csv";
  fs::remove(path);
  {
    BranchesCsv csv(path);
    long parent = 0, alpha = 0, beta = 0;
    for (int i = 1; i <= 100; ++i) {
      if (i % 4 == 0) {
        ++parent;
        (parent % 3 == 0 ? beta : alpha) += 1;
      }
      const double t = 0.01 * i;
      csv.write({{i, t, 0, 2.0, 3, parent}, {i, t, 1, 1.25, 2, alpha}, {i, t, 2, 0.75, 1, beta}});
    }
  }
  const cli::PhaseSeparationPoint p = cli::phase_separation_point(path, 0.5);
  EXPECT_DOUBLE_EQ(p.from_time, 0.5);
  EXPECT_DOUBLE_EQ(p.blood_fraction, 0.625);
  // Steps 50..100: passages at 52, 56, ..., 100 (13 of them, counted from step 49's total).
  EXPECT_EQ(p.parent_passages, 13);
  EXPECT_EQ(p.alpha_passages + p.beta_passages, 13);
  ASSERT_TRUE(p.cell_fraction);
  const double f = static_cast<double>(p.alpha_passages) / 13;
  EXPECT_DOUBLE_EQ(*p.cell_fraction, f);
  EXPECT_NEAR(*p.cell_fraction_stderr, std::sqrt(f * (1 - f) / 13), 1e-15);
  EXPECT_NEAR(f, 2.0 / 3, 0.06);
  const cli::ProportionInterval wilson = cli::wilson_interval(p.alpha_passages, 13, 1.0);
  EXPECT_EQ(*p.cell_fraction_low, wilson.low);
  EXPECT_EQ(*p.cell_fraction_high, wilson.high);
  EXPECT_LT(wilson.low, f);
  EXPECT_GT(wilson.high, f);
}

// The Wilson score interval against the published 95% intervals (z = 1.959964) of Newcombe's
// examples (Stat. Med. 17 (1998) 857, table I, method 3), given to 4 decimals: 81/263, 15/148,
// 0/20, 1/29. Its ends are where |k - n p| = z sqrt(n p (1 - p)) (checked to rounding at
// z = 1), and unlike the standard error it does not vanish at 0 or all successes.
TEST(StudyAnalysis, WilsonIntervalMatchesNewcombesTable) {
  struct Row {
    long k, n;
    double low, high;
  };
  for (const Row& r : {Row{81, 263, 0.2553, 0.3662}, Row{15, 148, 0.0624, 0.1605}, Row{0, 20, 0.0, 0.1611},
                       Row{1, 29, 0.0061, 0.1718}}) {
    const cli::ProportionInterval w = cli::wilson_interval(r.k, r.n, 1.959964);
    EXPECT_NEAR(w.low, r.low, 5e-5) << r.k << "/" << r.n;
    EXPECT_NEAR(w.high, r.high, 5e-5) << r.k << "/" << r.n;
  }
  const long k = 16, n = 17;
  const cli::ProportionInterval w = cli::wilson_interval(k, n, 1.0);
  for (double p : {w.low, w.high}) EXPECT_NEAR(std::abs(k - n * p), std::sqrt(n * p * (1 - p)), 1e-12);
  EXPECT_DOUBLE_EQ(cli::wilson_interval(17, 17, 1.0).high, 1.0);
  EXPECT_GT(1.0 - cli::wilson_interval(17, 17, 1.0).low, 0.05);  // 17 of 17: the standard error is 0
  EXPECT_THROW(cli::wilson_interval(3, 2, 1.0), std::invalid_argument);
  EXPECT_THROW(cli::wilson_interval(0, 0, 1.0), std::invalid_argument);
}

// The batch-means error of the cell fraction on passages written by hand, 20 over t in (0, 1]
// (two in each tenth): alpha takes both in the first five tenths and beta both in the last
// five, so f = 1/2, every batch's residual a_k - f n_k is +-1 and se^2 = 10/9 x 10 / 20^2:
// 1/6, where the binomial error of independent passages is sqrt(1/4 / 20) = 0.112. Had each
// tenth one of each, every batch would be the whole's image and the error 0.
TEST(StudyAnalysis, PhaseSeparationBatchErrorSeesTrains) {
  const fs::path path = fs::temp_directory_path() / "rbcflow_test_study_analysis_trains.csv";
  fs::remove(path);
  {
    BranchesCsv csv(path);
    long alpha = 0, beta = 0;
    for (int i = 1; i <= 100; ++i) {
      if (i % 5 == 3) (i <= 50 ? alpha : beta) += 1;  // steps 3 and 8 in the first tenth, ...
      const double t = 0.01 * i;
      csv.write({{i, t, 0, 2.0, 3, alpha + beta}, {i, t, 1, 1.0, 2, alpha}, {i, t, 2, 1.0, 1, beta}});
    }
  }
  const cli::PhaseSeparationPoint p = cli::phase_separation_point(path, 0.0);
  ASSERT_TRUE(p.cell_fraction && p.cell_fraction_batch_stderr);
  EXPECT_DOUBLE_EQ(*p.cell_fraction, 0.5);
  EXPECT_NEAR(*p.cell_fraction_stderr, std::sqrt(0.25 / 20), 1e-15);
  EXPECT_NEAR(*p.cell_fraction_batch_stderr, 1.0 / 6, 1e-15);
  EXPECT_DOUBLE_EQ(cli::batch_ratio_stderr(std::vector<long>(10, 1), std::vector<long>(10, 1)), 0.0);
  fs::remove(path);
}

// Independent passages: each of N = 400 goes to alpha with p = 0.7, spread over 10 batches
// by a multinomial draw. The ratio estimator's variance then has the binomial one as its mean:
// over 2,000 draws the mean of se_batch^2 / (f (1 - f) / N) is 1 to within 0.04 (the ratio has
// a relative spread of about sqrt(2 / 9) = 0.47 over 9 degrees of freedom, 0.0105 in a mean of
// 2,000: 3.8 of those; the estimator's bias is O(1 / N)).
TEST(StudyAnalysis, BatchErrorOfIndependentPassagesIsBinomial) {
  std::mt19937 rng(20261205);
  std::bernoulli_distribution to_alpha(0.7);
  std::uniform_int_distribution<int> batch(0, 9);
  double sum = 0;
  const int draws = 2000, n = 400;
  for (int d = 0; d < draws; ++d) {
    std::vector<long> alpha(10, 0), beta(10, 0);
    long a = 0;
    for (int i = 0; i < n; ++i) {
      const bool yes = to_alpha(rng);
      a += yes;
      (yes ? alpha : beta)[batch(rng)] += 1;
    }
    const double f = static_cast<double>(a) / n, se = cli::batch_ratio_stderr(alpha, beta);
    sum += se * se / (f * (1 - f) / n);
  }
  std::printf("mean of se_batch^2 / (f (1 - f) / N) over %d draws: %.4f\n", draws, sum / draws);
  EXPECT_NEAR(sum / draws, 1.0, 0.04);
  EXPECT_THROW(cli::batch_ratio_stderr({1}, {1}), std::invalid_argument);
  EXPECT_THROW(cli::batch_ratio_stderr({0, 0}, {0, 0}), std::invalid_argument);
  EXPECT_THROW(cli::batch_ratio_stderr({1, 2}, {1}), std::invalid_argument);
}

// The flows are time means: a run restarted at half the time step (docs/running.md) writes
// twice the rows a unit of time. Alpha carries 1.5 for t in (0.5, 1] (50 steps of 0.01) and
// 1.0 for t in (1, 1.5] (100 steps of 0.005), the parent 2.0 throughout: over t >= 0.5 alpha's
// mean is 1.25 and its fraction 0.625, where a mean of the rows would give 0.583.
TEST(StudyAnalysis, PhaseSeparationFlowsAreTimeMeans) {
  const fs::path path = fs::temp_directory_path() / "rbcflow_test_study_analysis_time_means.csv";
  fs::remove(path);
  {
    BranchesCsv csv(path);
    for (int i = 1; i <= 150; ++i) {
      const double t = i <= 50 ? 0.01 * (i + 50) : 1.0 + 0.005 * (i - 50);
      const double alpha = i <= 50 ? 1.5 : 1.0;
      csv.write({{i, t, 0, 2.0, 3, 0}, {i, t, 1, alpha, 2, 0}, {i, t, 2, 2.0 - alpha, 1, 0}});
    }
  }
  const cli::PhaseSeparationPoint p = cli::phase_separation_point(path, 1.0 / 3);
  EXPECT_DOUBLE_EQ(p.from_time, 0.5);
  EXPECT_NEAR(p.parent_flow, 2.0, 1e-14);
  EXPECT_NEAR(p.alpha_flow, 1.25, 1e-14);
  EXPECT_NEAR(p.blood_fraction, 0.625, 1e-14);
  fs::remove(path);
}
