// The frame model: validation of names and field sizes; merging cells into one surface.
#include "io/surface.h"

#include <gtest/gtest.h>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

namespace {

Surface sphere(double shift, double value) {
  SHSurface s = make_sphere(4);
  s.translate(Eigen::Vector3d(shift, 0, 0));
  Surface out{"cell", s.triangulate(SHTransform::gauss(4)), {}};
  out.fields.push_back({"tension", Eigen::MatrixXd::Constant(out.mesh.num_points(), 1, value)});
  out.fields.push_back({"velocity", Eigen::MatrixXd::Constant(out.mesh.num_points(), 3, -value)});
  return out;
}

}  // namespace

TEST(Surface, MergeConcatenatesPointsTrianglesAndFieldsAndAddsTheCellIndex) {
  const Surface a = sphere(0, 1), b = sphere(3, 2);
  const Surface m = merge_surfaces("cells", {a, b});
  const int n = a.mesh.num_points();
  EXPECT_EQ(m.name, "cells");
  ASSERT_EQ(m.mesh.num_points(), 2 * n);
  EXPECT_EQ(m.mesh.num_triangles(), 2 * a.mesh.num_triangles());
  EXPECT_EQ(m.mesh.points.row(n + 5), b.mesh.points.row(5));
  // Triangles of the second part index its own points.
  EXPECT_EQ(m.mesh.triangles.row(a.mesh.num_triangles()), (b.mesh.triangles.row(0).array() + n).matrix());
  ASSERT_EQ(m.fields.size(), 3u);
  EXPECT_EQ(m.fields[0].values(n + 1, 0), 2.0);
  EXPECT_EQ(m.fields[1].values(n - 1, 2), -1.0);
  EXPECT_EQ(m.fields[2].name, "cell");
  EXPECT_EQ(m.fields[2].values(n - 1, 0), 0.0);
  EXPECT_EQ(m.fields[2].values(n, 0), 1.0);
  EXPECT_EQ(merge_surfaces("cells", {}).mesh.num_points(), 0);
}

TEST(Surface, BadNamesAndSizesAreRejected) {
  Surface s = sphere(0, 1);
  EXPECT_NO_THROW(validate(s));
  s.fields[0].values.resize(3, 1);
  EXPECT_THROW(validate(s), std::invalid_argument);
  s = sphere(0, 1);
  s.fields[1].name = "tension";
  EXPECT_THROW(validate(s), std::invalid_argument);
  s = sphere(0, 1);
  s.fields[1].name = "a/b";
  EXPECT_THROW(validate(s), std::invalid_argument);
  s = sphere(0, 1);
  s.name = "";
  EXPECT_THROW(validate(s), std::invalid_argument);
  Surface other = sphere(1, 1);
  other.fields.pop_back();
  EXPECT_THROW(merge_surfaces("cells", {sphere(0, 1), other}), std::invalid_argument);
}
