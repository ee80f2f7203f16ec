#include "study_analysis.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/csv.h"

namespace rbcflow::cli {

namespace {

constexpr int kMaxBatches = 10;

double mean_of(const std::vector<double>& v, std::size_t begin, std::size_t end) {
  double s = 0;
  for (std::size_t i = begin; i < end; ++i) s += v[i];
  return s / static_cast<double>(end - begin);
}

// The time mean of rows [begin, end): each value weighted by its row's step, from the row
// before it (a run restarted at another time step writes rows of another length). Summed as
// differences from the first value, so that a constant is its own mean exactly.
double time_mean(const std::vector<double>& v, const std::vector<double>& step, std::size_t begin, std::size_t end) {
  double s = 0, w = 0;
  for (std::size_t i = begin; i < end; ++i) {
    s += step[i] * (v[i] - v[begin]);
    w += step[i];
  }
  return v[begin] + s / w;
}

// Each row's step: its time less the previous row's (the first row's, its time).
std::vector<double> row_steps(const CsvTable& table) {
  const std::size_t time = table.column("time");
  std::vector<double> step;
  double previous = 0;
  for (const auto& row : table.rows) {
    const double t = std::strtod(row[time].c_str(), nullptr);
    step.push_back(t - previous);
    previous = t;
  }
  return step;
}

enum class Summary { mean, largest, smallest };

// The time mean, largest or smallest value of a column over the rows with time >= from; empty
// when the column is missing or any of those rows has no value.
std::optional<double> column_summary(const CsvTable& table, const std::string& name, double from, Summary how) {
  const auto it = std::find(table.columns.begin(), table.columns.end(), name);
  if (it == table.columns.end()) return std::nullopt;
  const std::size_t col = static_cast<std::size_t>(it - table.columns.begin()), time = table.column("time");
  const std::vector<double> all_steps = row_steps(table);
  std::vector<double> v, step;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    if (std::strtod(row[time].c_str(), nullptr) < from) continue;
    if (row[col].empty()) return std::nullopt;
    v.push_back(std::strtod(row[col].c_str(), nullptr));
    step.push_back(all_steps[r]);
  }
  if (v.empty()) return std::nullopt;
  if (how == Summary::largest) return *std::max_element(v.begin(), v.end());
  if (how == Summary::smallest) return *std::min_element(v.begin(), v.end());
  return time_mean(v, step, 0, v.size());
}

}  // namespace

SteadyAverage steady_average(const std::filesystem::path& csv, int axis, double steady_fraction) {
  const CsvTable table = read_csv(csv);
  const std::size_t time = table.column("time"), mu = table.column("effective_viscosity");
  const std::size_t dp = table.column(std::string("pressure_gradient_") + "xyz"[axis]);
  if (table.rows.empty()) throw std::runtime_error(csv.string() + ": no rows");
  const double last = std::strtod(table.rows.back()[time].c_str(), nullptr);
  SteadyAverage a;
  a.from_time = steady_fraction * last;
  a.to_time = last;
  const std::vector<double> all_steps = row_steps(table);
  std::vector<double> viscosity, gradient, step;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    if (std::strtod(row[time].c_str(), nullptr) < a.from_time) continue;
    if (row[mu].empty()) throw std::runtime_error(csv.string() + ": no effective viscosity (a straight tube in a square box is needed)");
    viscosity.push_back(std::strtod(row[mu].c_str(), nullptr));
    gradient.push_back(std::strtod(row[dp].c_str(), nullptr));
    step.push_back(all_steps[r]);
  }
  if (viscosity.empty()) throw std::runtime_error(csv.string() + ": no rows in the steady part");
  const std::size_t n = viscosity.size();
  a.rows = static_cast<long>(n);
  a.mean = time_mean(viscosity, step, 0, n);
  // Batch means: consecutive rows are correlated; batches of n / B rows are nearly not.
  const int batches = static_cast<int>(std::min<std::size_t>(kMaxBatches, n / 2));
  if (n >= 4 && batches >= 2) {
    const std::size_t size = n / batches;
    std::vector<double> means;
    for (int b = 0; b < batches; ++b) means.push_back(time_mean(viscosity, step, b * size, (b + 1) * size));
    const double m = mean_of(means, 0, means.size());
    double var = 0;
    for (double x : means) var += (x - m) * (x - m);
    a.standard_error = std::sqrt(var / (batches - 1) / batches);
  }
  if (n >= 2) a.drift = (time_mean(viscosity, step, n - n / 2, n) - time_mean(viscosity, step, 0, n / 2)) / a.mean;
  const double g = time_mean(gradient, step, 0, n);
  a.pressure_gradient = g;
  a.tube_velocity = column_summary(table, "tube_velocity", a.from_time, Summary::mean);
  a.discharge_hematocrit = column_summary(table, "discharge_hematocrit", a.from_time, Summary::mean);
  a.max_area_strain = column_summary(table, "max_area_strain", a.from_time, Summary::largest);
  a.cell_free_layer = column_summary(table, "cell_free_layer", a.from_time, Summary::mean);
  a.min_wall_gap = column_summary(table, "min_wall_gap", a.from_time, Summary::smallest);
  const auto [lo, hi] = std::minmax_element(gradient.begin(), gradient.end());
  a.pressure_gradient_fluctuation = g != 0 ? (*hi - *lo) / std::abs(g) : 0.0;
  return a;
}

PhaseSeparationPoint phase_separation_point(const std::filesystem::path& csv, double steady_fraction) {
  const CsvTable table = read_csv(csv);
  const std::size_t time = table.column("time"), branch = table.column("branch"), flow = table.column("flow_rate");
  const std::size_t passed = table.column("cells_passed");
  if (table.rows.empty()) throw std::runtime_error(csv.string() + ": no rows");
  PhaseSeparationPoint p;
  p.to_time = std::strtod(table.rows.back()[time].c_str(), nullptr);
  p.from_time = steady_fraction * p.to_time;
  // Time means: a row's flow holds over its step, from the branch's row before it (a restart
  // may have changed the time step, docs/running.md); a row exactly at the window's start
  // weighs nothing.
  std::array<double, 3> flow_sum{}, weight_sum{}, previous{};
  std::array<long, 3> rows{}, before{}, last{};  // passages: the count before the window, and at its end
  // The daughters' passages in each batch of the window (by the row's time).
  std::vector<long> alpha_batches(kPassageBatches, 0), beta_batches(kPassageBatches, 0);
  const double span = p.to_time - p.from_time;
  for (const auto& row : table.rows) {
    const long b = std::strtol(row[branch].c_str(), nullptr, 10);
    if (b < 0 || b > 2) throw std::runtime_error(csv.string() + ": branch " + row[branch] + " (a bifurcation has 0, 1, 2)");
    const long n = std::strtol(row[passed].c_str(), nullptr, 10);
    const double t = std::strtod(row[time].c_str(), nullptr);
    if (t < p.from_time) {
      before[b] = n;
      previous[b] = t;
      continue;
    }
    if (b > 0 && span > 0) {
      const long new_passages = n - (rows[b] > 0 ? last[b] : before[b]);
      const int k = std::min(kPassageBatches - 1, static_cast<int>((t - p.from_time) / span * kPassageBatches));
      (b == 1 ? alpha_batches : beta_batches)[k] += new_passages;
    }
    last[b] = n;
    const double w = t - std::max(previous[b], p.from_time);
    flow_sum[b] += w * std::strtod(row[flow].c_str(), nullptr);
    weight_sum[b] += w;
    previous[b] = t;
    ++rows[b];
  }
  for (int b = 0; b < 3; ++b)
    if (rows[b] == 0 || weight_sum[b] <= 0)
      throw std::runtime_error(csv.string() + ": no rows of branch " + std::to_string(b) + " in the steady part");
  p.parent_flow = flow_sum[0] / weight_sum[0];
  p.alpha_flow = flow_sum[1] / weight_sum[1];
  p.beta_flow = flow_sum[2] / weight_sum[2];
  p.blood_fraction = p.alpha_flow / p.parent_flow;
  p.parent_passages = last[0] - before[0];
  p.alpha_passages = last[1] - before[1];
  p.beta_passages = last[2] - before[2];
  const long n = p.alpha_passages + p.beta_passages;
  if (n > 0) {
    const double f = static_cast<double>(p.alpha_passages) / static_cast<double>(n);
    p.cell_fraction = f;
    p.cell_fraction_stderr = std::sqrt(f * (1 - f) / static_cast<double>(n));
    const ProportionInterval wilson = wilson_interval(p.alpha_passages, n, 1.0);
    p.cell_fraction_low = wilson.low;
    p.cell_fraction_high = wilson.high;
    int filled = 0;
    for (int k = 0; k < kPassageBatches; ++k) filled += alpha_batches[k] + beta_batches[k] > 0;
    if (filled >= 2) p.cell_fraction_batch_stderr = batch_ratio_stderr(alpha_batches, beta_batches);
  }
  return p;
}

double batch_ratio_stderr(const std::vector<long>& alpha, const std::vector<long>& beta) {
  if (alpha.size() != beta.size() || alpha.size() < 2)
    throw std::invalid_argument("batch_ratio_stderr: needs two or more batches, as many of alpha as of beta");
  double a = 0, n = 0;
  for (std::size_t k = 0; k < alpha.size(); ++k) a += alpha[k], n += alpha[k] + beta[k];
  if (!(n > 0)) throw std::invalid_argument("batch_ratio_stderr: no passages");
  const double f = a / n, batches = static_cast<double>(alpha.size());
  double sum = 0;
  for (std::size_t k = 0; k < alpha.size(); ++k) {
    const double r = alpha[k] - f * (alpha[k] + beta[k]);
    sum += r * r;
  }
  return std::sqrt(batches / (batches - 1) * sum) / n;
}

ProportionInterval wilson_interval(long successes, long trials, double z) {
  if (trials <= 0 || successes < 0 || successes > trials || !(z > 0))
    throw std::invalid_argument("wilson_interval: needs 0 <= successes <= trials, trials > 0, z > 0");
  const double k = static_cast<double>(successes), n = static_cast<double>(trials), z2 = z * z;
  const double centre = (k + 0.5 * z2) / (n + z2);
  const double half = z / (n + z2) * std::sqrt(k * (n - k) / n + 0.25 * z2);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace rbcflow::cli
