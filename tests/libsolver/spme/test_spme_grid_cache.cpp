#include "libsolver/spme/spme_grid_cache.h"

#include <gtest/gtest.h>

using namespace rbcflow;

// One grid per (kernel, tolerance, box, counts), with the parameters a fresh choice gives.
TEST(SpmeGridCache, SameKeySameGridOtherKeyOtherGrid) {
  SpmeGridCache cache;
  const PeriodicBox box(Eigen::Vector3d(4.0, 5.0, 6.0));
  const auto a = cache.grid(EwaldKernel::stokeslet, 1e-6, box, 1000);
  EXPECT_EQ(cache.grid(EwaldKernel::stokeslet, 1e-6, box, 1000), a);
  EXPECT_NE(cache.grid(EwaldKernel::stresslet, 1e-6, box, 1000), a);
  EXPECT_NE(cache.grid(EwaldKernel::stokeslet, 1e-6, box, 1000, 50), a);
  EXPECT_NE(cache.grid(EwaldKernel::stokeslet, 1e-5, box, 1000), a);
  const EwaldParameters fresh = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, 1000).parameters;
  EXPECT_EQ(a->parameters().xi, fresh.xi);
  EXPECT_EQ(a->parameters().grid, fresh.grid);
  EXPECT_EQ(a->parameters().order, fresh.order);
  EXPECT_EQ(ewald_grid(nullptr, EwaldKernel::stokeslet, 1e-6, box, 1000)->parameters().xi, fresh.xi);
}
