// Files written by the ranks together (parallel HDF5): a checkpoint (io/checkpoint.h,
// CheckpointWriter::write with Ranks) and an XDMF series (io/xdmf_writer.h with Ranks), run
// under mpirun -np 2 and 3 (tests/io/CMakeLists.txt). Each rank spoils the rows it does not
// write, so a file equals the intended whole only if every rank wrote exactly its own rows; a
// scalar is rank 0's. A checkpoint that cannot be written fails on every rank and leaves nothing
// behind.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>

#include "io/checkpoint.h"
#include "io/xdmf_reader.h"
#include "io/xdmf_writer.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int ranks() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// Contiguous blocks of n rows, the first n % p ranks one row more.
std::pair<long long, long long> block(long long n, int r, int p) {
  const long long base = n / p, extra = n % p;
  const long long begin = r * base + std::min<long long>(r, extra);
  return {begin, begin + base + (r < extra ? 1 : 0)};
}

// The same directory on every rank (rank 0's process id).
fs::path shared_dir() {
  long id = rank() == 0 ? static_cast<long>(::getpid()) : 0L;
  MPI_Bcast(&id, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  return fs::temp_directory_path() / ("rbcflow_shared_checkpoint_" + std::to_string(id));
}

CheckpointWriter::Ranks world_ranks() {
  return {static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD)), rank(), "test",
          [](const std::string&, long long rows) { return block(rows, rank(), ranks()); }};
}

}  // namespace

TEST(SharedCheckpoint, EachRankWritesItsRows) {
  ASSERT_TRUE(CheckpointWriter::shared_by_ranks());
  const fs::path dir = shared_dir();
  if (rank() == 0) fs::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  const fs::path file = dir / "step.h5";

  Eigen::MatrixXd whole(11, 3);
  Eigen::MatrixXi labels(7, 2);
  for (int i = 0; i < whole.rows(); ++i)
    for (int j = 0; j < 3; ++j) whole(i, j) = std::sin(1.0 + i + 0.3 * j);
  for (int i = 0; i < labels.rows(); ++i) labels.row(i) << i, 10 * i;
  Eigen::MatrixXd held = whole;  // what this rank holds: wrong outside its rows
  Eigen::MatrixXi held_labels = labels;
  const auto [b, e] = block(whole.rows(), rank(), ranks());
  for (int i = 0; i < held.rows(); ++i)
    if (i < b || i >= e) held.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  const auto [lb, le] = block(labels.rows(), rank(), ranks());
  for (int i = 0; i < held_labels.rows(); ++i)
    if (i < lb || i >= le) held_labels.row(i).setConstant(-1);

  // A part only: the rows the rank gives, the last rank's first (not the blocks' order), and
  // a part no rank but the last gives (a cell's coefficients held by one rank).
  Eigen::MatrixXd history(13, 3);
  for (int i = 0; i < history.rows(); ++i)
    for (int j = 0; j < 3; ++j) history(i, j) = std::cos(2.0 + i + 0.7 * j);
  const auto [hb, he] = block(history.rows(), ranks() - 1 - rank(), ranks());
  const bool last = rank() == ranks() - 1;

  CheckpointWriter w("fingerprint");
  w.put("cells/velocity", held);
  w.put("wall/labels", held_labels);
  w.put_rows("cells/history", history.rows(), hb, history.middleRows(hb, he - hb));
  w.put_rows("cells/7/coefficients", 4, 0, last ? Eigen::MatrixXd(whole.topRows(4)) : Eigen::MatrixXd(0, 3));
  w.put("steps", rank() == 0 ? 42LL : -1LL);
  w.put("time", rank() == 0 ? 0.25 : -1.0);
  w.put("case", std::string("title = \"x\""));
  w.write(file, world_ranks());
  MPI_Barrier(MPI_COMM_WORLD);

  const Checkpoint k = Checkpoint::read(file, "fingerprint");
  EXPECT_EQ(k.matrix("cells/velocity"), whole);
  EXPECT_EQ(k.int_matrix("wall/labels"), labels);
  EXPECT_EQ(k.matrix("cells/history"), history);
  EXPECT_EQ(k.matrix("cells/7/coefficients"), whole.topRows(4));
  EXPECT_EQ(k.integer("steps"), 42);
  EXPECT_EQ(k.real("time"), 0.25);
  EXPECT_EQ(k.text("case"), "title = \"x\"");
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++entries;
    EXPECT_EQ(entry.path().filename(), "step.h5");  // no temporary left
  }
  EXPECT_EQ(entries, 1);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0) fs::remove_all(dir);
}

TEST(SharedCheckpoint, AFailedWriteFailsOnEveryRank) {
  const fs::path missing = shared_dir() / "no_such_directory" / "step.h5";
  CheckpointWriter w("fingerprint");
  w.put("steps", 1LL);
  try {
    w.write(missing, world_ranks());
    ADD_FAILURE() << "writing into a missing directory did not fail on rank " << rank();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write the checkpoint " + missing.string()), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(missing));
}

// Two frames of a surface of 9 points and 4 triangles, with a vector field: each rank spoils
// the points, triangles and field rows it does not write. The second frame's triangles are a
// link to the first's; the XML is rank 0's.
TEST(SharedFrames, EachRankWritesItsRows) {
  ASSERT_TRUE(XdmfWriter::shared_by_ranks());
  const fs::path dir = shared_dir();
  if (rank() == 0) fs::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  Surface whole{"cells", {}, {}};
  whole.mesh.points.resize(9, 3);
  whole.mesh.triangles.resize(4, 3);
  for (int i = 0; i < 9; ++i) whole.mesh.points.row(i) << i, std::cos(i), 0.5 * i * i;
  for (int t = 0; t < 4; ++t) whole.mesh.triangles.row(t) << 2 * t, 2 * t + 1, 2 * t + 2;
  whole.fields = {{"velocity", whole.mesh.points * 2.0}};
  const auto spoiled = [&](double shift) {
    Surface s = whole;
    s.mesh.points.array() += shift;
    s.fields[0].values.array() += shift;
    const auto [b, e] = block(9, rank(), ranks());
    const auto [tb, te] = block(4, rank(), ranks());
    for (int i = 0; i < 9; ++i) {
      if (i >= b && i < e) continue;
      s.mesh.points.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
      s.fields[0].values.row(i).setConstant(-7.0);
    }
    for (int t = 0; t < 4; ++t)
      if (t < tb || t >= te) s.mesh.triangles.row(t).setConstant(-1);
    return s;
  };
  {
    XdmfWriter w(dir, std::nullopt, "rbcflow",
                 XdmfWriter::Ranks{static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD)), rank(),
                                   [](const std::string&, long long rows) { return block(rows, rank(), ranks()); },
                                   {}});
    w.write_frame(10, 0.5, {spoiled(0.0)});
    w.write_frame(20, 1.0, {spoiled(1.0)});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  ASSERT_EQ(read_xdmf_frames(dir).size(), 2u);
  for (const double shift : {0.0, 1.0}) {
    const XdmfFrame f = read_xdmf_frame(dir, shift == 0.0 ? 10 : 20);
    ASSERT_EQ(f.surfaces.size(), 1u);
    EXPECT_EQ(f.surfaces[0].mesh.triangles, whole.mesh.triangles);
    EXPECT_EQ(f.surfaces[0].mesh.points, (whole.mesh.points.array() + shift).matrix());
    EXPECT_EQ(f.surfaces[0].fields[0].values, (whole.fields[0].values.array() + shift).matrix());
  }
  EXPECT_TRUE(fs::exists(dir / "rbcflow.xdmf"));
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0) fs::remove_all(dir);
}

// Each rank gives write_frame only its part of a surface (XdmfWriter::SurfacePart): two cells
// of 3 points and 2 triangles, rank r the cells of its block (none on the third of 3 ranks),
// the triangles numbered as in the whole. The file holds the whole surface; the second frame's
// triangles, the same on every rank, are a link to the first's; in the third only rank 0's
// points are the second's, and every rank writes them.
TEST(SharedFrames, EachRankGivesItsPart) {
  ASSERT_TRUE(XdmfWriter::shared_by_ranks());
  const fs::path dir = shared_dir() / "parts";
  if (rank() == 0) fs::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  Surface whole{"cells", {}, {}};
  whole.mesh.points.resize(6, 3);
  whole.mesh.triangles.resize(4, 3);
  for (int i = 0; i < 6; ++i) whole.mesh.points.row(i) << i, std::sin(i), 0.25 * i;
  for (int c = 0; c < 2; ++c) {
    whole.mesh.triangles.row(2 * c) << 3 * c, 3 * c + 1, 3 * c + 2;
    whole.mesh.triangles.row(2 * c + 1) << 3 * c + 2, 3 * c + 1, 3 * c;
  }
  whole.fields = {{"J_S", whole.mesh.points.col(0) * 0.1}};
  const auto [first, end] = block(2, rank(), ranks());  // this rank's cells
  const auto part = [&](double shift) {
    Surface s{"cells", {}, {}};
    s.mesh.points = whole.mesh.points.middleRows(3 * first, 3 * (end - first));
    s.mesh.points.array() += shift;
    s.mesh.triangles = whole.mesh.triangles.middleRows(2 * first, 2 * (end - first));
    s.fields = {{"J_S", whole.fields[0].values.middleRows(3 * first, 3 * (end - first))}};
    return s;
  };
  const std::map<std::string, XdmfWriter::SurfacePart> parts{{"cells", {3 * first, 6, 2 * first, 4}}};
  {
    XdmfWriter w(dir, std::nullopt, "rbcflow",
                 XdmfWriter::Ranks{static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD)), rank(),
                                   [](const std::string&, long long rows) { return block(rows, rank(), ranks()); },
                                   [](bool mine) {
                                     int all = mine ? 1 : 0;
                                     MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
                                     return all == 1;
                                   }});
    w.write_frame(10, 0.5, {part(0.0)}, parts);
    w.write_frame(20, 1.0, {part(1.0)}, parts);
    w.write_frame(30, 1.5, {part(rank() == 0 ? 1.0 : 2.0)}, parts);  // rank 0's points as in frame 20
  }
  MPI_Barrier(MPI_COMM_WORLD);
  ASSERT_EQ(read_xdmf_frames(dir).size(), 3u);
  for (const long step : {10L, 20L, 30L}) {
    const XdmfFrame f = read_xdmf_frame(dir, step);
    ASSERT_EQ(f.surfaces.size(), 1u);
    EXPECT_EQ(f.surfaces[0].mesh.triangles, whole.mesh.triangles) << "step " << step;
    Eigen::MatrixXd expected = whole.mesh.points;
    if (step == 20) expected.array() += 1.0;
    if (step == 30) {
      const auto [b0, e0] = block(2, 0, ranks());
      expected.array() += 2.0;
      expected.middleRows(3 * b0, 3 * (e0 - b0)) = whole.mesh.points.middleRows(3 * b0, 3 * (e0 - b0)).array() + 1.0;
    }
    EXPECT_EQ(f.surfaces[0].mesh.points, expected) << "step " << step;
    EXPECT_EQ(f.surfaces[0].fields[0].values, whole.fields[0].values) << "step " << step;
  }
  // An XDMF series of one process takes no parts.
  if (rank() == 0) {
    fs::create_directories(dir / "alone");
    XdmfWriter alone(dir / "alone");
    EXPECT_THROW(alone.write_frame(0, 0.0, {whole}, {{"cells", {0, 6, 0, 4}}}), std::invalid_argument);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0) fs::remove_all(dir);
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int failed = RUN_ALL_TESTS() != 0 ? 1 : 0;
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any;
}
