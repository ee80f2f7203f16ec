#pragma once
// rbcflow study on bifurcations: phase separation (Pries et al. 1989, 2005). For each run, the
// fraction of the parent's blood flow that daughter alpha (branch 1) receives and the fraction
// of the cells, from its branches.csv over the steady part (study_analysis.h), against the
// empirical law at the run's diameters and measured H_D (libsolver/wall/pries_law.h): written
// to DIR/phase_separation.csv and plotted in DIR/phase_separation.png.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/case.h"
#include "io/csv.h"
#include "io/study_plot.h"

namespace rbcflow::cli {

class PhaseSeparationStudy {
 public:
  PhaseSeparationStudy(std::filesystem::path out, bool quiet);
  // One finished run of the bifurcation case `c` in c.output.dir.
  void add(const Case& c, const std::string& name, double steady_fraction);
  // The plot (throws std::runtime_error when no run was added).
  void finish();

 private:
  std::filesystem::path out_;
  bool quiet_;
  std::optional<CsvWriter> csv_;
  StudyPlot plot_;
  std::vector<double> laws_;  // the law at each plotted point, -1 where it has none
};

}  // namespace rbcflow::cli
