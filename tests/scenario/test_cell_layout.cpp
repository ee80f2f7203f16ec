// Listed cells: orientations, placement, and the box / vessel / overlap checks (through
// prepare_scenario, as run and check meet them).
#include "scenario/cell_layout.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scenario/scenario.h"

using namespace rbcflow;

namespace {

// A D = 3.2 tube along z in a 4 x 4 x 4 box and the given [cells] lines.
Case tube(const std::string& cells, double diameter = 3.2) {
  return parse_case("[domain]\nbox = [4, 4, 4]\nmean_velocity = [0, 0, 1]\n[vessel]\ndiameter = " +
                        std::to_string(diameter) + "\n[cells]\n" + cells,
                    "layout.toml");
}

std::string layout_error(const Case& c) {
  try {
    prepare_scenario(c);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CellLayout, OrientationsAreGivenOrSeededRandom) {
  CaseCells c;
  c.positions = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  const auto a = cell_orientations(c), b = cell_orientations(c);
  EXPECT_EQ(a, b);
  for (const Vec3& u : a) EXPECT_NEAR(std::hypot(u[0], u[1], u[2]), 1.0, 1e-15);
  c.seed = 2;
  EXPECT_NE(cell_orientations(c), a);
  c.orientations = {{0, 0, 2}, {1, 0, 0}, {0, 3, 4}};
  EXPECT_EQ(cell_orientations(c)[2], (Vec3{0, 0.6, 0.8}));
}

TEST(CellLayout, PlacedCellsKeepVolumeAndSitAtTheirPositions) {
  CaseCells c;
  c.positions = {{1, 2, 3}};
  c.orientations = {{1, 0, 0}};
  const SHSurface s = placed_cells(c, 12)[0];
  const SurfaceGeometry g = s.geometry(SHTransform::gauss(12));
  EXPECT_NEAR(enclosed_volume(g), 4 * M_PI / 3, 1e-6);
  EXPECT_NEAR((volume_centroid(g) - Eigen::Vector3d(1, 2, 3)).norm(), 0, 1e-10);
  // The disc's symmetry axis is now x: its thickness is along x.
  const Eigen::Vector3d extent = g.x.colwise().maxCoeff() - g.x.colwise().minCoeff();
  EXPECT_LT(extent.x(), 1.0);
  EXPECT_GT(extent.y(), 2.5);
}

TEST(CellLayout, AxisymmetricPairFits) {
  // Section 11.1: two cells on the axis of a D = 3.2 tube, 2 apart.
  EXPECT_EQ(layout_error(tube("positions = [[2, 2, 1], [2, 2, 3]]\norientations = [[0, 0, 1], [0, 0, 1]]\n")), "");
}

TEST(CellLayout, OverlapIsAnErrorNamingThePositionsLine) {
  EXPECT_EQ(layout_error(tube("positions = [[2, 2, 1], [2, 2, 1.4]]\norientations = [[0, 0, 1], [0, 0, 1]]\n")),
            "layout.toml:7: cells.positions: cells 0 at [2, 2, 1] and 1 at [2, 2, 1.4] overlap (or within the "
            "collision threshold 0.02)");
  // Through the periodic boundary: z = 0.2 and z = 3.8 are 0.4 apart.
  EXPECT_NE(layout_error(tube("positions = [[2, 2, 0.2], [2, 2, 3.8]]\norientations = [[0, 0, 1], [0, 0, 1]]\n"))
                .find("overlap"),
            std::string::npos);
}

TEST(CellLayout, CellCrossingTheWallIsAnError) {
  // A disc of radius 1.39 lying across a D = 2.4 tube.
  const std::string e = layout_error(tube("positions = [[2, 2, 2]]\norientations = [[0, 0, 1]]\n", 2.4));
  EXPECT_NE(e.find("layout.toml:7: cells.positions: cell 0 at [2, 2, 2] crosses the vessel wall"), std::string::npos)
      << e;
  // In a D = 3.2 tube it fits on the axis, but not 0.3 off it (1.39 + 0.3 > 1.6).
  EXPECT_EQ(layout_error(tube("positions = [[2, 2, 2]]\norientations = [[0, 0, 1]]\n")), "");
  EXPECT_NE(layout_error(tube("positions = [[2.3, 2, 2]]\norientations = [[0, 0, 1]]\n")).find("crosses"),
            std::string::npos);
}

TEST(CellLayout, CellLongerThanTheBoxIsAnError) {
  const Case c = parse_case(
      "[domain]\nbox = [2, 2, 10]\nmean_velocity = [0, 0, 1]\n[cells]\npositions = [[1, 1, 5]]\n"
      "orientations = [[0, 0, 1]]\n",
      "small.toml");
  EXPECT_NE(layout_error(c).find("longer than the periodic box"), std::string::npos);
}
