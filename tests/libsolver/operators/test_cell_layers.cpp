// CellLayers and CellLayersAtPoints built for the step's one single-layer density (cell_layers.h):
// the single layer computed at construction, with the single-layer tables and plan freed as
// they are used, is the single layer the kept tables give, for two red cells close enough to
// need nearly-singular corrections, in a periodic box and in free space.
#include "libsolver/operators/cell_layers.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/operators/cell_layers_at_points.h"

using namespace rbcflow;

namespace {

std::vector<SHCoeffs> two_close_cells(int N) {
  SHSurface a = make_biconcave(N), b = make_biconcave(N);
  a.translate(Eigen::Vector3d(2.0, 2.0, 2.0));
  b.translate(Eigen::Vector3d(2.1, 2.3, 2.0 + 0.95));  // the dimples 0.1-0.2 apart: near targets
  return {a.coeffs(), b.coeffs()};
}

Eigen::MatrixXd smooth_density(const PointField& x) {
  Eigen::MatrixXd f(x.rows(), 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    f.row(i) << std::sin(x(i, 1)) + 0.2, x(i, 0) * x(i, 2), std::cos(x(i, 0) - x(i, 2));
  return f;
}

}  // namespace

TEST(CellLayers, SingleLayerOfTheStepDensityEqualsTheKeptTables) {
  const int N = 12;
  const auto grids = CellGrids::make(N, 2 * N);
  for (const bool periodic : {true, false}) {
    LayerDomain domain;
    if (periodic) domain = LayerDomain{PeriodicBox(Eigen::Vector3d(4.5, 4.5, 5.0)), 1e-8};
    CellLayers kept(two_close_cells(N), grids, domain);
    ASSERT_GT(kept.near_targets(), 0);
    const Eigen::MatrixXd f = smooth_density(kept.nodes().x);
    CellLayers once(two_close_cells(N), grids, domain, {}, true, nullptr, &f);
    const Eigen::MatrixXd expected = kept.single_layer(f);
    const double difference = (once.single_layer(f) - expected).norm() / expected.norm();
    std::printf("  %s: single layer of the step density against the kept tables: %.1e\n",
                periodic ? "periodic" : "free space", difference);
    EXPECT_LT(difference, 1e-14);
    // The double layer is untouched by it.
    const Eigen::MatrixXd u = smooth_density(kept.nodes().x + kept.nodes().normal);
    EXPECT_LT((once.double_layer(u) - kept.double_layer(u)).norm(), 1e-14 * kept.double_layer(u).norm());
    EXPECT_THROW(once.single_layer(2 * f), std::logic_error);

    // At points off the cells, some of them within the near distance.
    Eigen::MatrixXd points(4, 3);
    points << 2.0, 2.0, 2.6, 2.0, 2.0, 0.5, 3.5, 2.0, 2.0, 2.05, 2.15, 2.47;
    const CellLayersAtPoints at_kept(kept, points);
    const CellLayersAtPoints at_once(kept, points, &f);
    ASSERT_GT(at_kept.near_points(), 0);
    const Eigen::MatrixXd at_expected = at_kept.single_layer(f);
    EXPECT_LT((at_once.single_layer(f) - at_expected).norm(), 1e-14 * at_expected.norm());
    EXPECT_THROW(at_once.single_layer(2 * f), std::logic_error);
  }
}

// The double layer's Ewald choice keeps its pair coefficients within the plans' bound where a
// choice there meets the tolerance (tube27: 13,824 nodes), and falls back to the default choice
// where none does: the 512,000 nodes of data/cases/tube_1000_cells.toml need more than 2e8
// pairs at any cutoff the grid limit allows, which the bounded chooser refuses.
TEST(CellLayers, DoubleLayerKeepsPairsOnlyWhereTheBoundAllows) {
  const PeriodicBox tube27(Eigen::Vector3d(6.6, 6.6, 13.33));
  const RealSpaceUse kept = double_layer_real_space(kMaxKeptPairs, 1e-6, tube27, 13824);
  EXPECT_EQ(kept.weight, 0.2);
  EXPECT_EQ(kept.max_pairs, static_cast<double>(kMaxKeptPairs));
  const RealSpaceUse none = double_layer_real_space(0, 1e-6, tube27, 13824);
  EXPECT_EQ(none.weight, RealSpaceUse{}.weight);

  const PeriodicBox tube1000(Eigen::Vector3d(12.6, 12.6, 123.56));
  const long nodes = 512000;
  EXPECT_THROW(choose_ewald_parameters(EwaldKernel::stresslet, 1e-6, tube1000, nodes, nodes,
                                       RealSpaceUse{0.2, static_cast<double>(kMaxKeptPairs)}),
               std::invalid_argument);
  const RealSpaceUse fallback = double_layer_real_space(kMaxKeptPairs, 1e-6, tube1000, nodes);
  EXPECT_EQ(fallback.weight, RealSpaceUse{}.weight);
  EXPECT_EQ(fallback.max_pairs, RealSpaceUse{}.max_pairs);
  const EwaldChoice c = choose_ewald_parameters(EwaldKernel::stresslet, 1e-6, tube1000, nodes, nodes, fallback);
  EXPECT_GT(c.neighbours_per_target * nodes, static_cast<double>(kMaxKeptPairs));  // the plans will not keep them
}
