#pragma once
// The PNGs of a study: measured points with error bars over a reference curve and its band (a
// tube study: the effective viscosity against the tube diameter, paper fig. 13, over the Pries
// law +-10%; a bifurcation study: the cells' split against the blood's); and curves of one
// quantity per tube.
#include <filesystem>
#include <string>
#include <vector>

namespace rbcflow {

struct StudyPlot {
  std::string title;
  std::string x_title = "tube diameter D (um)", y_title = "effective viscosity mu_eff / mu";
  std::vector<double> diameter, value;  // the measured points
  std::vector<double> bar_low, bar_high;  // each point's error bar, its ends (equal: no bar)
  std::vector<double> reference_diameter, reference, reference_low, reference_high;  // low, high: a +-10% band, or none
  std::string reference_name = "reference";
  // The reference at each point's own condition (the Pries law at the run's measured H_D),
  // drawn as crosses at the points' diameters; empty: none.
  std::vector<double> reference_at_points;
  std::string reference_at_points_name;
  // Further reference curves under the points, each in its own colour (the phase-separation
  // law at each run's own diameters and H_D).
  struct Curve {
    std::string name;
    std::vector<double> x, y;
  };
  std::vector<Curve> reference_curves;
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
