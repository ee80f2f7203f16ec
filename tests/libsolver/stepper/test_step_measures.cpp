// What a step measures besides the flow. The cells' volume flux (libsolver/stepper/cell_flux.h), integral_V u_a dV from the surface
// velocity, against exact values for solenoidal fields whose volume integral is known: a uniform
// translation (V v), a rigid rotation about a point p (V (omega x (c - p))), and the linear field
// u = x e_z (V c_x), c the volume centroid. The cells are off-centre, turned discs and
// ellipsoids, so that nothing cancels by symmetry.
#include "libsolver/stepper/cell_flux.h"
#include "libsolver/stepper/cell_free_layer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/membrane/membrane_law.h"
#include "libsolver/stepper/cell_stepper.h"

using namespace rbcflow;

namespace {

constexpr int kOrder = 12;

std::vector<SHSurface> cells() {
  SHSurface disc = make_biconcave(kOrder);
  disc.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix());
  disc.translate(Eigen::Vector3d(0.3, -1.1, 2.0));
  SHSurface ellipsoid = make_ellipsoid(kOrder, Eigen::Vector3d(0.8, 0.9, 1.3));
  ellipsoid.rotate(Eigen::AngleAxisd(-1.2, Eigen::Vector3d(0.2, 1, 1).normalized()).toRotationMatrix());
  ellipsoid.translate(Eigen::Vector3d(2.5, 0.4, -0.7));
  return {disc, ellipsoid};
}

// The field at every grid point of every cell, stacked.
template <class Field>
Eigen::MatrixXd sampled(const std::vector<SHSurface>& s, const SHTransform& grid, Field u) {
  const Eigen::Index np = grid.grid().size();
  Eigen::MatrixXd out(np * static_cast<Eigen::Index>(s.size()), 3);
  for (std::size_t c = 0; c < s.size(); ++c) {
    const SurfaceGeometry g = s[c].geometry(grid);
    for (Eigen::Index p = 0; p < np; ++p) out.row(static_cast<Eigen::Index>(c) * np + p) = u(Eigen::Vector3d(g.x.row(p))).transpose();
  }
  return out;
}

}  // namespace

TEST(CellFlux, VolumeIntegralsOfSolenoidalFieldsAreExact) {
  const std::vector<SHSurface> s = cells();
  const SHTransform grid = SHTransform::gauss(kOrder);
  double volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // sum V c
  for (const SHSurface& c : s) {
    const SurfaceGeometry g = c.geometry(grid);
    volume += enclosed_volume(g);
    moment += enclosed_volume(g) * volume_centroid(g);
  }
  const Eigen::Vector3d v(0.4, -0.3, 1.7), omega(0.5, -1.0, 0.8), p(1.0, 2.0, -0.5);
  for (int a = 0; a < 3; ++a) {
    const double translation = cells_volume_flux(s, sampled(s, grid, [&](const Eigen::Vector3d&) { return v; }), grid, a);
    EXPECT_NEAR(translation, volume * v[a], 1e-12 * volume) << "axis " << a;
    const double rotation = cells_volume_flux(
        s, sampled(s, grid, [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(omega.cross(x - p)); }), grid, a);
    EXPECT_NEAR(rotation, omega.cross(moment - volume * p)[a], 1e-11 * volume) << "axis " << a;
  }
  const double shear =
      cells_volume_flux(s, sampled(s, grid, [](const Eigen::Vector3d& x) { return Eigen::Vector3d(0, 0, x.x()); }), grid, 2);
  EXPECT_NEAR(shear, moment.x(), 1e-11 * volume);
  EXPECT_THROW(cells_volume_flux(s, Eigen::MatrixXd::Zero(3, 3), grid, 2), std::invalid_argument);
  EXPECT_THROW(cells_volume_flux(s, sampled(s, grid, [&](const Eigen::Vector3d&) { return v; }), grid, 3),
               std::invalid_argument);
}

// StepReport::max_area_strain: a sphere of rest radius 1 held at radius 1.1 has J_S = 1.21 at
// every point of its membrane, so the largest |J_S - 1| is 0.21; beside one held at 1.05
// (0.1025), listed first, the report names the second cell.
TEST(StepReport, AreaStrainOfAUniformlyDilatedSphere) {
  const auto grids = CellGrids::make(8, 16);
  const SHSurface rest = make_sphere(8);
  std::vector<Cell> cells(2);
  for (int k = 0; k < 2; ++k) {
    cells[k].membrane = std::make_shared<const Membrane>(
        rest, grids, MembraneParameters{std::make_shared<SkalakLaw>(12.4, 200.0), 0.0669});
    cells[k].shape = make_sphere(8, k == 0 ? 1.05 : 1.1);
    cells[k].shape.translate(Eigen::Vector3d(5.0 * k, 0, 0));
  }
  CellStepperOptions o;
  o.dt = 1e-5;
  CellStepper stepper(cells, grids, o);
  const StepReport r = stepper.step();
  EXPECT_NEAR(r.max_area_strain, 0.21, 1e-10);
  EXPECT_EQ(r.max_area_strain_cell, 1);
}

// The cell-free layer against its value for spheres centred on the axis of a tube of radius R:
// in every sector the outermost membrane point is on the Gauss colatitude nearest the equator,
// at rho max_i sin(theta_i) from the axis. Two spheres in the two halves of the period (one of
// them a period further on: cells are not wrapped) give the mean of their two layers.
TEST(CellFreeLayer, SpheresOnTheAxisOfATube) {
  const int order = 16;
  const SHTransform grid = SHTransform::gauss(order);
  double outermost = 0.0;  // max_i sin(theta_i)
  for (const double theta : grid.grid().theta()) outermost = std::max(outermost, std::sin(theta));
  const double R = 2.0, period = 6.0;
  const TubeSection tube{Eigen::Vector3d(3.0, 3.0, 0.0), 2, R};
  SHSurface small = make_sphere(order, 0.8), large = make_sphere(order, 1.2);
  small.translate(Eigen::Vector3d(3.0, 3.0, 1.5));
  large.translate(Eigen::Vector3d(3.0, 3.0, 4.5 + period));
  EXPECT_NEAR(cell_free_layer({small}, grid, tube, period, {period, 16}), R - 0.8 * outermost, 1e-12);
  EXPECT_NEAR(cell_free_layer({small, large}, grid, tube, period, {0.5 * period, 16}),
              R - 0.5 * (0.8 + 1.2) * outermost, 1e-12);
  EXPECT_THROW(cell_free_layer({}, grid, tube, period), std::invalid_argument);
}

// The volume constraint's correction (section 10.2) is the volume error of the move it
// corrects: one step of a red cell in a free-space shear flow, from the same state with the
// constraint and without it (the move is the same: the constraint acts after it), reports as
// correction with it the volume error without it, and leaves a volume error below 1e-10
// (its two normal shifts converge quadratically) that no longer shows the move's.
TEST(StepReport, VolumeCorrectionIsTheVolumeErrorOfTheMove) {
  const auto grids = CellGrids::make(10, 20);
  Cell c;
  c.membrane = std::make_shared<const Membrane>(
      make_biconcave(10), grids, MembraneParameters{std::make_shared<SkalakLaw>(1.0, 10.0), 0.01});
  // Stretched off its rest shape, so that the membrane drives a disturbance flow (a linear
  // background alone moves the surface affinely, keeping its volume to rounding).
  c.shape = make_ellipsoid(10, Eigen::Vector3d(1.2, 0.9, 0.5));
  c.shape.rotate(Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix());
  auto step_with = [&](bool constraint) {
    CellStepperOptions o;
    o.dt = 5e-2;
    o.background = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x.z(), 0, 0); };
    o.volume_constraint = constraint;
    CellStepper stepper({c}, grids, o);
    return stepper.step();
  };
  const StepReport free = step_with(false), held = step_with(true);
  EXPECT_FALSE(free.max_volume_correction.has_value());
  ASSERT_TRUE(held.max_volume_correction.has_value());
  EXPECT_GT(free.max_volume_error, 1e-8);  // the move's error is there to be seen
  EXPECT_NEAR(*held.max_volume_correction, free.max_volume_error, 1e-14);
  EXPECT_LT(held.max_volume_error, 1e-10);
}
