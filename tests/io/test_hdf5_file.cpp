// The HDF5 layer: matrices row-major both ways, attributes, scalars, groups in creation order,
// soft links, and errors that name the object.
#include "io/hdf5_file.h"

#include <gtest/gtest.h>

using namespace rbcflow;
namespace fs = std::filesystem;

TEST(Hdf5File, MatricesScalarsAndAttributesRoundTrip) {
  const fs::path path = fs::temp_directory_path() / "rbcflow_test_hdf5.h5";
  Eigen::MatrixXd m(4, 3);
  m << 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12;
  {
    const h5::QuietErrors quiet;
    const h5::Id f = h5::create_file(path);
    const h5::Id g = h5::create_group(f.get(), "zeta");
    h5::create_group(f.get(), "alpha");
    h5::write_matrix(g.get(), "m", m);
    h5::write_matrix(g.get(), "v", Eigen::MatrixXd(m.col(1)), true);
    h5::write_matrix(g.get(), "i", Eigen::MatrixXi(Eigen::MatrixXi::Identity(2, 3)));
    h5::write_scalar(f.get(), "pi", 3.25);
    h5::write_scalar(f.get(), "n", 42LL);
    h5::write_scalar(f.get(), "s", std::string("text"));
    h5::write_attribute(f.get(), "a", std::string("attr"));
    h5::write_attribute(g.get(), "t", 0.5);
    h5::write_attribute(g.get(), "k", 7LL);
    h5::soft_link(f.get(), "link", "/zeta/m");
  }
  const h5::Id f = h5::open_file(path, false);
  EXPECT_EQ(h5::children(f.get()), (std::vector<std::string>{"alpha", "link", "n", "pi", "s", "zeta"}));
  const h5::Id g = h5::open_group(f.get(), "zeta");
  EXPECT_EQ(h5::children(g.get()), (std::vector<std::string>{"m", "v", "i"}));  // creation order
  EXPECT_EQ(h5::read_matrix(g.get(), "m"), m);
  EXPECT_EQ(h5::shape(g.get(), "m"), (std::vector<hsize_t>{4, 3}));
  EXPECT_EQ(h5::shape(g.get(), "v"), (std::vector<hsize_t>{4}));
  EXPECT_EQ(h5::read_matrix(g.get(), "v"), m.col(1));
  EXPECT_EQ(h5::read_int_matrix(g.get(), "i"), Eigen::MatrixXi::Identity(2, 3));
  EXPECT_EQ(h5::read_matrix(f.get(), "link"), m);
  EXPECT_EQ(h5::read_real(f.get(), "pi"), 3.25);
  EXPECT_EQ(h5::read_integer(f.get(), "n"), 42);
  EXPECT_EQ(h5::read_text(f.get(), "s"), "text");
  EXPECT_EQ(h5::read_string_attribute(f.get(), "a"), "attr");
  EXPECT_EQ(h5::read_double_attribute(g.get(), "t"), 0.5);
  EXPECT_EQ(h5::read_int_attribute(g.get(), "k"), 7);
  EXPECT_TRUE(h5::exists(f.get(), "zeta/m"));
  EXPECT_FALSE(h5::exists(f.get(), "zeta/q"));
  EXPECT_FALSE(h5::exists(f.get(), "nope/q"));
  EXPECT_EQ(h5::dataset_info(f.get(), "s").kind, h5::Kind::text);
  EXPECT_EQ(h5::dataset_info(g.get(), "i").rank, 2);
  EXPECT_EQ(h5::all_datasets(f.get()).size(), 6u);  // each dataset once; the soft link is no object
  fs::remove(path);
}

TEST(Hdf5File, ErrorsNameTheObject) {
  const fs::path path = fs::temp_directory_path() / "rbcflow_test_hdf5_errors.h5";
  const h5::QuietErrors quiet;
  const h5::Id f = h5::create_file(path);
  try {
    h5::read_matrix(f.get(), "missing");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "HDF5: no dataset missing");
  }
  h5::write_scalar(f.get(), "x", 1.0);
  EXPECT_THROW(h5::write_scalar(f.get(), "x", 2.0), std::runtime_error);  // exists
  EXPECT_THROW(h5::read_int_attribute(f.get(), "none"), std::runtime_error);
  EXPECT_THROW(h5::open_file("/nonexistent/x.h5", false), std::runtime_error);
  h5::create_parents(f.get(), "a/b/c");
  EXPECT_TRUE(h5::exists(f.get(), "a/b"));
  fs::remove(path);
}
