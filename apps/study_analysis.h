#pragma once
// The statistics of a study: for a tube (paper section 11.2), from a run's diagnostics.csv, the
// effective viscosity (45)-(46) averaged over the statistically steady part of the run, its
// standard error by batch means, its drift across the averaged part, and the fluctuation of the
// mean pressure gradient; for a bifurcation, from its branches.csv, the split of blood and cells.
#include <filesystem>
#include <optional>
#include <vector>

namespace rbcflow::cli {

struct SteadyAverage {
  long rows = 0;             // diagnostics rows averaged
  double from_time = 0;      // start of the steady part
  double to_time = 0;
  double mean = 0;           // effective viscosity
  double standard_error = 0; // batch means (up to 10 batches; 0 with fewer than 4 rows)
  // (mean over the second half of the steady part - mean over its first half) / mean: a run
  // still settling shows a drift larger than a few standard errors (0 with fewer than 2 rows).
  double drift = 0;
  double pressure_gradient_fluctuation = 0;  // (max - min) / |mean| of <dp/ds> along the axis
  double pressure_gradient = 0;              // mean <dp/ds> along the axis
  // Means over the same rows of the tube's measured flow (empty where diagnostics.csv has no
  // value: runs before these columns, or no cells), the largest local area strain and the
  // closest approach of a cell to the wall.
  std::optional<double> tube_velocity, discharge_hematocrit, max_area_strain, cell_free_layer, min_wall_gap;
};

// Rows with time >= steady_fraction x the last time; means are time means, each row weighted by
// its step from the row before it (a run restarted at another time step writes rows of another
// length; at one time step, the rows' means). Throws std::runtime_error naming the file
// when it has no effective viscosity (no straight tube) or no rows in the steady part.
SteadyAverage steady_average(const std::filesystem::path& diagnostics_csv, int axis, double steady_fraction);

// The split at a bifurcation (branches.csv: 0 the parent, 1 daughter alpha, 2 daughter beta)
// over the rows with time >= steady_fraction x the last time: the fraction of the parent's
// blood flow that alpha receives (mean flows), and of the cells (the passages through the
// daughters' mid-sections in that time, from the last count before it or the run's start; the
// parent's for its discharge hematocrit).
struct PhaseSeparationPoint {
  double from_time = 0, to_time = 0;
  double parent_flow = 0, alpha_flow = 0, beta_flow = 0;  // time means
  double blood_fraction = 0;                              // alpha / parent
  long parent_passages = 0, alpha_passages = 0, beta_passages = 0;
  // alpha / (alpha + beta) passages, and its binomial standard error sqrt(f (1 - f) / n): each
  // cell reaching the split goes one way or the other; empty without passages. low, high: its
  // Wilson score interval at z = 1 (the coverage of +- one standard error, 68%), which stays
  // honest at a handful of passages with f near 0 or 1, where the standard error shrinks to 0.
  std::optional<double> cell_fraction, cell_fraction_stderr, cell_fraction_low, cell_fraction_high;
  // The standard error of the cell fraction by batch means (batch_ratio_stderr over the window
  // cut into kPassageBatches equal times): near the binomial one where passages are
  // independent, larger where cells go one way in trains. Empty unless passages fall in at
  // least two batches.
  std::optional<double> cell_fraction_batch_stderr;
};

inline constexpr int kPassageBatches = 10;

// The standard error of the ratio f = sum a_k / sum (a_k + b_k) from its batches (a_k, b_k:
// the passages through alpha and beta in batch k), treating the batches, not the passages, as
// independent: the ratio estimator's variance (W. G. Cochran, Sampling Techniques, 3rd ed.,
// Wiley 1977, ch. 6),
//   se^2 = K / (K - 1) sum_k (a_k - f n_k)^2 / N^2,   n_k = a_k + b_k, N = sum n_k, K batches,
// whose mean is the binomial f (1 - f) / N when every passage is independent. Throws
// std::invalid_argument on batches of different counts, fewer than two or no passage.
double batch_ratio_stderr(const std::vector<long>& alpha, const std::vector<long>& beta);

// The Wilson score interval of a binomial proportion: `successes` of `trials` (> 0), at z
// standard normal deviates (E. B. Wilson, J. Am. Stat. Assoc. 22 (1927) 209; R. G. Newcombe,
// Stat. Med. 17 (1998) 857, method 3): the p with |k - n p| <= z sqrt(n p (1 - p)),
//   (k + z^2 / 2) / (n + z^2) -+ z / (n + z^2) sqrt(k (n - k) / n + z^2 / 4).
struct ProportionInterval {
  double low = 0, high = 0;
};
ProportionInterval wilson_interval(long successes, long trials, double z);

// Throws std::runtime_error naming the file when it has not three branches or no rows in the
// steady part.
PhaseSeparationPoint phase_separation_point(const std::filesystem::path& branches_csv, double steady_fraction);

}  // namespace rbcflow::cli
