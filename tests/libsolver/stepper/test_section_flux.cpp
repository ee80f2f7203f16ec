// The volume flux through a vessel's cross-sections (libsolver/stepper/section_flux.h), in the
// straight periodic tube of test_tube_drive (D = 3.5 in a 5 x 5 x 3 box).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"
#include "geometry/vessel/vessel_branch.h"
#include "libsolver/membrane/membrane_law.h"
#include "libsolver/stepper/cell_stepper.h"

using namespace rbcflow;

namespace {

constexpr double kD = 3.5, kSide = 5.0, kLength = 3.0, kPi = std::numbers::pi;
const Eigen::Vector3d kBox(kSide, kSide, kLength);

std::shared_ptr<const WallElements> tube_wall(double h) {
  TubeSpec spec;
  spec.diameter = kD;
  spec.box = kBox;
  spec.element_size = h;
  return std::make_shared<const WallElements>(tube(spec));
}

// The tube's cross-section at z.
SectionQuadrature section_at(double z) {
  const Eigen::Vector3d c(0.5 * kSide, 0.5 * kSide, z);
  return section_quadrature({c - Eigen::Vector3d::UnitZ(), c + Eigen::Vector3d::UnitZ(), 0.5 * kD});
}

}  // namespace

// Without cells the flow in the tube is Poiseuille's for the wall's mean pressure gradient G:
// Q = pi a^4 G / 8 (mu = 1). The sections' quadrature is exact for it; what remains is the
// wall's discretisation error, second order in h.
TEST(SectionFlux, PoiseuilleFluxWithoutCells) {
  double previous = 0;
  for (double h : {kD / 8, kD / 16}) {
    CellStepperOptions o;
    o.domain = LayerDomain{PeriodicBox(kBox), 1e-8};
    o.mean_velocity = Eigen::Vector3d::UnitZ();
    o.wall = tube_wall(h);
    o.wall_solve = WallSolveOptions{1e-9, 300, 60};
    o.flux_sections = {{section_at(0.3 * kLength)}, {section_at(0.8 * kLength)}};
    CellStepper stepper({}, nullptr, o);
    const StepReport r = stepper.step();
    ASSERT_EQ(r.section_flux.size(), 2u);
    const double a = 0.5 * kD, exact = kPi * std::pow(a, 4) * -r.pressure_gradient.z() / 8;
    const double error = std::max(std::abs(r.section_flux[0] / exact - 1), std::abs(r.section_flux[1] / exact - 1));
    std::printf("h = D/%.0f: flux %.6f, %.6f; Poiseuille for the wall's G %.6f (rel. error %.2e)\n", kD / h,
                r.section_flux[0], r.section_flux[1], exact, error);
    // The same flow at both, up to where each disk reaches past the faceted wall (an O(h^2)
    // sliver at O(h) velocity; measured 5.7e-5 and 5.5e-6 of the flux).
    EXPECT_NEAR(r.section_flux[0], r.section_flux[1], 1e-4 * exact);
    if (previous > 0) {
      EXPECT_LT(error, 5e-3);
      EXPECT_GT(std::log2(previous / error), 1.5);
    }
    previous = error;
  }
}

// With a red cell (lambda = 5) on the axis (N = 12, h = D/12), the tube velocity held at 2.
// The flux through a section clear of the cell equals the tube's, pi a^2 U, held by the tube
// meter (tube_drive.h: exact with cells up to its cell-free calibration, 0.6% at D/16 in
// test_tube_drive). A branch with sections through the cell and one clear of it measures
// through the clear one. Through the cell, the points inside it are divided by lambda (without,
// the flux would be off by about (lambda - 1) x the cell's share of the section, 200%); the
// velocity gradient jumps at the membrane, which the 8 x 24 quadrature resolves to 0.5%
// (sections 0 .. 0.4 from the cell's middle, measured: -0.01% .. +0.6%).
TEST(SectionFlux, ThroughTheSectionClearOfTheCells) {
  const auto grids = CellGrids::make(12, 24);
  SHSurface s = make_biconcave(12);
  s.translate(Eigen::Vector3d(0.5 * kSide, 0.5 * kSide, 0.5 * kLength));
  Cell c;
  c.membrane = std::make_shared<const Membrane>(s, grids,
                                                MembraneParameters{std::make_shared<SkalakLaw>(12.4, 200.0), 0.0669});
  c.shape = std::move(s);
  CellStepperOptions o;
  o.dt = 2e-3;
  o.viscosity_ratio = 5.0;
  o.domain = LayerDomain{PeriodicBox(kBox), 1e-7};
  o.wall = tube_wall(kD / 12);
  o.tube = TubeSection{Eigen::Vector3d(0.5 * kSide, 0.5 * kSide, 0.0), 2, 0.5 * kD};
  o.tube_velocity = 2.0;
  o.gmres_tolerance = 1e-8;
  const double middle = 0.5 * kLength;
  o.flux_sections = {{section_at(middle)},
                     {section_at(middle + 0.1)},
                     {section_at(middle + 0.4)},
                     {section_at(0.0)},
                     {section_at(middle), section_at(middle + 0.1), section_at(0.0), section_at(middle - 0.4)}};
  CellStepper stepper({c}, grids, o);
  const FlowSolution f = stepper.solve();
  const double tube = kPi * 0.25 * kD * kD * *f.tube_velocity, clear = f.section_flux[3];
  std::printf("flux through the cell's middle %.6f, 0.1 and 0.4 off it %.6f, %.6f; clear of it %.6f; "
              "the branch of four sections %.6f; pi a^2 U %.6f\n",
              f.section_flux[0], f.section_flux[1], f.section_flux[2], clear, f.section_flux[4], tube);
  EXPECT_NEAR(clear, tube, 1e-2 * tube);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(f.section_flux[i], clear, 1e-2 * clear);
  }
  // The branch's clearest section is the one in the box face, the same as the clear branch's
  // (evaluated in another batch of points: the same sums to rounding and the Ewald tolerance).
  EXPECT_NEAR(f.section_flux[4], clear, 1e-6 * clear);
}
