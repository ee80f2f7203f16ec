#include "phase_separation_study.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "libsolver/wall/pries_law.h"
#include "scenario/derived.h"
#include "scenario/physical_units.h"
#include "study_analysis.h"

namespace rbcflow::cli {

namespace fs = std::filesystem;

namespace {

// The law's FQ_E over FQ_B in [0, 1] (0 below X0, 1 above 1 - X0), named by its diameters and
// H_D: the whole curve each point is compared with, not only its value there.
StudyPlot::Curve law_curve(const PhaseSeparationLaw& law) {
  char name[160];
  std::snprintf(name, sizeof name, "Pries et al. 2005: %.3g um -> %.3g / %.3g um, H_D %.2f", law.parent_um,
                law.alpha_um, law.beta_um, law.discharge_hematocrit);
  StudyPlot::Curve c{name, {}, {}};
  constexpr int kSamples = 400;
  for (int i = 0; i <= kSamples; ++i) {
    const double fq_b = static_cast<double>(i) / kSamples;
    c.x.push_back(fq_b);
    c.y.push_back(law.cell_fraction(fq_b));
  }
  return c;
}

}  // namespace

PhaseSeparationStudy::PhaseSeparationStudy(fs::path out, bool quiet) : out_(std::move(out)), quiet_(quiet) {
  plot_.title = "Phase separation at the bifurcation: daughter alpha's share";
  plot_.x_title = "fraction of the parent's blood flow FQ_B";
  plot_.y_title = "fraction of the parent's red cells FQ_E";
  plot_.reference_name = "no separation (FQ_E = FQ_B)";
  plot_.reference_at_points_name = "Pries et al. 2005 at each run's diameters and H_D";
  plot_.reference_diameter = {0.0, 1.0};
  plot_.reference = {0.0, 1.0};
}

void PhaseSeparationStudy::add(const Case& c, const std::string& name, double steady_fraction) {
  if (!csv_) {
    csv_.emplace(out_ / "phase_separation.csv",
                 std::vector<std::string>{"case", "parent_um", "alpha_um", "beta_um", "steady_from", "time",
                                          "parent_flow", "alpha_flow", "beta_flow", "blood_fraction",
                                          "parent_passages", "alpha_passages", "beta_passages", "cell_fraction",
                                          "cell_fraction_stderr", "cell_fraction_low", "cell_fraction_high",
                                          "discharge_hematocrit", "pries_2005", "cell_fraction_batch_stderr"});
  }
  const PhaseSeparationPoint p = phase_separation_point(c.output.dir / "branches.csv", steady_fraction);
  const PhysicalUnits si(c.units);
  const double parent = si.micrometres(c.vessel->diameter);
  const double alpha = si.micrometres(c.vessel->daughter_diameters[0]);
  const double beta = si.micrometres(c.vessel->daughter_diameters[1]);
  // The parent's discharge hematocrit: the cells' volume through its section over the blood's.
  const double span = p.to_time - p.from_time;
  std::optional<double> hd, law;
  if (span > 0 && p.parent_flow > 0) {
    hd = p.parent_passages * reference_cell(*c.cells).volume / (p.parent_flow * span);
    // The law holds for 0 <= H_D < 1; a window too short for the passages to average gives more.
    if (*hd < 1) law = PhaseSeparationLaw{parent, alpha, beta, *hd}.cell_fraction(p.blood_fraction);
  }
  csv_->write({name, csv_number(parent), csv_number(alpha), csv_number(beta), csv_number(p.from_time),
               csv_number(p.to_time), csv_number(p.parent_flow), csv_number(p.alpha_flow), csv_number(p.beta_flow),
               csv_number(p.blood_fraction), std::to_string(p.parent_passages), std::to_string(p.alpha_passages),
               std::to_string(p.beta_passages), csv_number(p.cell_fraction), csv_number(p.cell_fraction_stderr),
               csv_number(p.cell_fraction_low), csv_number(p.cell_fraction_high),
               csv_number(hd), csv_number(law), csv_number(p.cell_fraction_batch_stderr)});
  if (!quiet_) {
    std::printf("%s: parent %.3g um, daughters %.3g and %.3g um; over t in [%.4g, %.4g] alpha takes %.3f of the blood",
                name.c_str(), parent, alpha, beta, p.from_time, p.to_time, p.blood_fraction);
    if (p.cell_fraction) {
      std::printf(" and %.3f +- %.3f of the cells (%ld passages; Wilson 68%% interval %.3f-%.3f)", *p.cell_fraction,
                  *p.cell_fraction_stderr, p.alpha_passages + p.beta_passages, *p.cell_fraction_low,
                  *p.cell_fraction_high);
      if (p.cell_fraction_batch_stderr) std::printf(", batch-means s.e. %.3f", *p.cell_fraction_batch_stderr);
      if (law) std::printf("; Pries 2005 at the parent's H_D %.3f: %.3f", *hd, *law);
    } else {
      std::printf(" (no cell passed either daughter in that time)");
    }
    std::printf("\n");
  }
  if (p.cell_fraction) {
    plot_.diameter.push_back(p.blood_fraction);
    plot_.value.push_back(*p.cell_fraction);
    plot_.bar_low.push_back(*p.cell_fraction_low);
    plot_.bar_high.push_back(*p.cell_fraction_high);
    laws_.push_back(law.value_or(-1));
    if (law) plot_.reference_curves.push_back(law_curve(PhaseSeparationLaw{parent, alpha, beta, *hd}));
  }
}

void PhaseSeparationStudy::finish() {
  if (!csv_) throw std::runtime_error("rbcflow study: every run failed; nothing to plot");
  if (plot_.diameter.empty()) {
    std::printf("study: %s (no cell passages yet: no plot; run longer)\n", (out_ / "phase_separation.csv").c_str());
    return;
  }
  // The law's crosses where every point has one (a window long enough for the parent's H_D).
  if (std::none_of(laws_.begin(), laws_.end(), [](double v) { return v < 0; })) plot_.reference_at_points = laws_;
  plot_study(plot_, out_ / "phase_separation.png");
  std::printf("study: %s, %s\n", (out_ / "phase_separation.csv").c_str(), (out_ / "phase_separation.png").c_str());
}

}  // namespace rbcflow::cli
