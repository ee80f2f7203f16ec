// An XDMF series read back: the frames' steps and times, and a frame's surfaces with their
// fields exactly as written (the wall's points, a soft link after the first frame, included).
#include "io/xdmf_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/input_error.h"
#include "io/xdmf_writer.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

Surface triangle(const std::string& name, double shift) {
  Surface s{name, {}, {}};
  s.mesh.points.resize(3, 3);
  s.mesh.points << 0, 0, shift, 1, 0, shift, 0, 1, shift;
  s.mesh.triangles.resize(1, 3);
  s.mesh.triangles << 0, 1, 2;
  Eigen::MatrixXd v(3, 3);
  v << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  s.fields = {{"velocity", shift * v}, {"tension", Eigen::VectorXd::Constant(3, shift)}};
  return s;
}

}  // namespace

TEST(XdmfReader, FramesReadBackAsWritten) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_xdmf_reader";
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    XdmfWriter w(dir);
    for (long step : {0, 5, 10}) w.write_frame(step, 0.1 * step, {triangle("cells", step), triangle("wall", 0.0)});
  }
  const std::vector<XdmfFrameTime> frames = read_xdmf_frames(dir);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[1].step, 5);
  EXPECT_DOUBLE_EQ(frames[2].time, 1.0);
  const XdmfFrame f = read_xdmf_frame(dir, 10);
  ASSERT_EQ(f.surfaces.size(), 2u);
  const Surface expected = triangle("cells", 10);
  EXPECT_EQ(f.surfaces[0].name, "cells");
  EXPECT_EQ(f.surfaces[0].mesh.points, expected.mesh.points);
  EXPECT_EQ(f.surfaces[0].mesh.triangles, expected.mesh.triangles);
  ASSERT_EQ(f.surfaces[0].fields.size(), 2u);
  EXPECT_EQ(f.surfaces[0].fields[0].name, "velocity");
  EXPECT_EQ(f.surfaces[0].fields[0].values, expected.fields[0].values);
  EXPECT_EQ(f.surfaces[0].fields[1].values.rows(), 3);
  EXPECT_EQ(f.surfaces[1].mesh.points, triangle("wall", 0.0).mesh.points);  // through the soft link
  try {
    read_xdmf_frame(dir, 7);
    ADD_FAILURE() << "no frame at step 7";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no frame at step 7 (saved: 0, 5, 10)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_xdmf_frames(dir / "none"), InputError);
  fs::remove_all(dir);
}
