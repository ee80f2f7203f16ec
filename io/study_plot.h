#pragma once
// The PNGs of a tube study: the measured effective viscosity against the tube diameter (paper
// fig. 13), with error bars, over a reference curve and its band (the Pries law +-10%); and
// curves of one quantity per tube.
#include <filesystem>
#include <string>
#include <vector>

namespace rbcflow {

struct StudyPlot {
  std::string title;
  std::vector<double> diameter, value, error;  // the measured points (error: +- one bar)
  std::vector<double> reference_diameter, reference, reference_low, reference_high;
  std::string reference_name = "reference";
  // The reference at each point's own condition (the Pries law at the run's measured H_D),
  // drawn as crosses at the points' diameters; empty: none.
  std::vector<double> reference_at_points;
  std::string reference_at_points_name;
};

// Writes `png` atomically; throws std::runtime_error when there is no display or it cannot.
void plot_study(const StudyPlot& plot, const std::filesystem::path& png, int width = 1000, int height = 700);

// Curves on common axes, one per tube (the radial hematocrit profiles of a study).
struct CurvesPlot {
  std::string title, x_title, y_title;
  std::vector<std::string> names;
  std::vector<std::vector<double>> x, y;
};
void plot_curves(const CurvesPlot& plot, const std::filesystem::path& png, int width = 1000, int height = 700);

}  // namespace rbcflow
