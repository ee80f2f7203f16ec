// Checkpoints: exact round trip of every item type, atomic replacement (also when the writer
// is killed), and clear errors for truncated, foreign and other-case files.
#include "io/checkpoint.h"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <thread>

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string error_of(const fs::path& file, const std::string& fingerprint = "0123456789abcdef") {
  try {
    Checkpoint::read(file, fingerprint);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

int files_in(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST(Checkpoint, EveryItemTypeRoundTripsExactly) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint");
  Eigen::MatrixXd coeffs(256, 3);
  coeffs.setRandom();
  coeffs(0, 0) = 1.0 / 3.0;
  Eigen::MatrixXi triangles(5, 3);
  triangles.setRandom();
  CheckpointWriter w("0123456789abcdef");
  w.put("cells/0/coefficients", coeffs);
  w.put("cells/0/reference", coeffs * 2);
  w.put("wall/triangles", triangles);
  w.put("history/velocity", Eigen::MatrixXd(0, 3));
  w.put("column", Eigen::MatrixXd::Ones(4, 1));
  w.put("step", 123456789012LL);
  w.put("time", 0.1 + 0.2);
  w.put("scheme", std::string("ab2"));
  w.put("empty", std::string());
  w.write(dir / "step_00000010.h5");
  EXPECT_EQ(files_in(dir), 1);  // no temporary left

  const Checkpoint c = Checkpoint::read(dir / "step_00000010.h5", "0123456789abcdef");
  EXPECT_EQ(c.matrix("cells/0/coefficients"), coeffs);
  EXPECT_EQ(c.matrix("cells/0/reference"), coeffs * 2);
  EXPECT_EQ(c.int_matrix("wall/triangles"), triangles);
  EXPECT_EQ(c.matrix("history/velocity").rows(), 0);
  EXPECT_EQ(c.matrix("history/velocity").cols(), 3);
  EXPECT_EQ(c.matrix("column").cols(), 1);
  EXPECT_EQ(c.integer("step"), 123456789012LL);
  EXPECT_EQ(c.real("time"), 0.1 + 0.2);
  EXPECT_EQ(c.text("scheme"), "ab2");
  EXPECT_EQ(c.text("empty"), "");
  EXPECT_EQ(c.names().size(), 9u);
  EXPECT_TRUE(c.has("wall/triangles"));
  EXPECT_FALSE(c.has("wall"));
  fs::remove_all(dir);
}

TEST(Checkpoint, MissingOrMistypedItemNamesFileAndItem) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint_items");
  CheckpointWriter w("f");
  w.put("step", 3LL);
  w.write(dir / "c.h5");
  const Checkpoint c = Checkpoint::read(dir / "c.h5", "f");
  try {
    c.matrix("cells/0/coefficients");
    FAIL();
  } catch (const CheckpointError& e) {
    EXPECT_EQ(std::string(e.what()), "checkpoint " + (dir / "c.h5").string() + " has no item cells/0/coefficients");
  }
  EXPECT_THROW(c.real("step"), CheckpointError);
  EXPECT_THROW(w.put("step", 4LL), std::invalid_argument);
  EXPECT_THROW(w.put("/abs", 4LL), std::invalid_argument);
  fs::remove_all(dir);
}

// Items read by rows (a rank reading its own cells' of a restart): their size and any block of
// their rows equal the whole item's, bit for bit, with the file read on demand; the other items
// are read whole; matrix() of such an item and rows outside it are CheckpointErrors naming them.
TEST(Checkpoint, ItemsReadByRowsAreTheWholeItemsRows) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint_by_rows");
  Eigen::MatrixXd velocity(40, 3), coeffs(16, 3);
  velocity.setRandom();
  coeffs.setRandom();
  CheckpointWriter w("f");
  w.put("cells/previous_velocity", velocity);
  w.put("cells/0/coefficients", coeffs);
  w.put("column", Eigen::VectorXd::LinSpaced(4, 0.0, 3.0));
  w.put("wall/previous_force", velocity * 2);
  w.write(dir / "c.h5");
  const auto by_rows = [](const std::string& name) { return name.starts_with("cells/") || name == "column"; };
  const Checkpoint c = Checkpoint::read(dir / "c.h5", "f", by_rows);
  EXPECT_TRUE(c.has("cells/previous_velocity"));
  EXPECT_EQ(c.matrix_size("cells/previous_velocity"), std::make_pair(40LL, 3LL));
  EXPECT_EQ(c.rows("cells/previous_velocity", 12, 20), velocity.middleRows(12, 20));
  EXPECT_EQ(c.rows("cells/previous_velocity", 0, 40), velocity);
  EXPECT_EQ(c.rows("cells/previous_velocity", 40, 0).rows(), 0);
  EXPECT_EQ(c.rows("cells/0/coefficients", 0, 16), coeffs);
  EXPECT_EQ(c.matrix_size("column"), std::make_pair(4LL, 1LL));
  EXPECT_EQ(c.rows("column", 1, 2), Eigen::Vector2d(1.0, 2.0));
  EXPECT_EQ(c.matrix("wall/previous_force"), velocity * 2);  // read whole
  EXPECT_EQ(c.rows("wall/previous_force", 39, 1), velocity.bottomRows(1) * 2);
  const std::string file = (dir / "c.h5").string();
  try {
    c.matrix("cells/previous_velocity");
    FAIL();
  } catch (const CheckpointError& e) {
    EXPECT_EQ(std::string(e.what()), "checkpoint " + file + ": item cells/previous_velocity is read by rows (rows())");
  }
  try {
    c.rows("cells/previous_velocity", 30, 11);
    FAIL();
  } catch (const CheckpointError& e) {
    EXPECT_EQ(std::string(e.what()), "checkpoint " + file + ": item cells/previous_velocity has 40 rows, not rows 30 to 41");
  }
  EXPECT_THROW(c.rows("cells/older_velocity", 0, 1), CheckpointError);
  fs::remove_all(dir);
}

// put_rows in a file of one process: every row, or a clear error naming the item; rows beyond
// the matrix are refused when put.
TEST(Checkpoint, RowsOfOneProcessAreEveryRow) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint_rows");
  const Eigen::MatrixXd m = Eigen::MatrixXd::Constant(5, 3, 0.5);
  CheckpointWriter whole("f");
  whole.put_rows("cells/previous_velocity", 5, 0, m);
  whole.write(dir / "whole.h5");
  EXPECT_EQ(Checkpoint::read(dir / "whole.h5", "f").matrix("cells/previous_velocity"), m);

  CheckpointWriter part("f");
  part.put_rows("cells/previous_velocity", 8, 3, m);
  try {
    part.write(dir / "part.h5");
    FAIL() << "a part of the rows written by one process";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("item cells/previous_velocity: a part of its rows in a file of one process"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "part.h5"));
  EXPECT_THROW(part.put_rows("cells/older_velocity", 4, 0, m), std::invalid_argument);
  fs::remove_all(dir);
}

TEST(Checkpoint, AnotherCaseIsRejected) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint_case");
  CheckpointWriter("aaaaaaaaaaaaaaaa").write(dir / "c.h5");
  const std::string e = error_of(dir / "c.h5", "bbbbbbbbbbbbbbbb");
  EXPECT_NE(e.find("was written for another case (case fingerprint aaaaaaaaaaaaaaaa, this case bbbbbbbbbbbbbbbb)"),
            std::string::npos)
      << e;
  fs::remove_all(dir);
}

TEST(Checkpoint, TruncatedForeignAndMissingFilesAreClearErrors) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint_bad");
  CheckpointWriter w("0123456789abcdef");
  w.put("cells/0/coefficients", Eigen::MatrixXd::Random(2000, 3));
  w.put("step", 7LL);
  w.write(dir / "good.h5");
  // Truncated to half, as by a full disk or an interrupted copy.
  fs::copy_file(dir / "good.h5", dir / "truncated.h5");
  fs::resize_file(dir / "truncated.h5", fs::file_size(dir / "good.h5") / 2);
  const std::string truncated = error_of(dir / "truncated.h5");
  EXPECT_NE(truncated.find("truncated"), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("truncated.h5"), std::string::npos) << truncated;
  // Truncated to its first kilobyte.
  fs::copy_file(dir / "good.h5", dir / "head.h5");
  fs::resize_file(dir / "head.h5", 1024);
  EXPECT_NE(error_of(dir / "head.h5").find("head.h5"), std::string::npos);
  std::ofstream(dir / "text.h5") << "not a checkpoint\n";
  EXPECT_NE(error_of(dir / "text.h5").find("not an HDF5 file"), std::string::npos);
  EXPECT_NE(error_of(dir / "none.h5").find("none.h5: no such file"), std::string::npos);
  // An HDF5 file that is not a checkpoint.
  {
    const hid_t f = H5Fcreate((dir / "other.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Fclose(f);
  }
  EXPECT_NE(error_of(dir / "other.h5").find("not an rbcflow checkpoint"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Checkpoint, FailedWriteLeavesTheEarlierCheckpoint) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint_fail");
  CheckpointWriter good("f");
  good.put("step", 1LL);
  good.write(dir / "c.h5");
  CheckpointWriter bad("f");
  bad.put("a", 2LL);
  bad.put("a/b", 3LL);  // "a" cannot be a dataset and a group: HDF5 fails mid-write
  EXPECT_THROW(bad.write(dir / "c.h5"), std::runtime_error);
  EXPECT_EQ(Checkpoint::read(dir / "c.h5", "f").integer("step"), 1);
  EXPECT_EQ(files_in(dir), 1);
  EXPECT_THROW(good.write("/nonexistent-dir/c.h5"), std::runtime_error);
  fs::remove_all(dir);
}

TEST(Checkpoint, KillDuringWritesLeavesAGoodCheckpoint) {
  const fs::path dir = fresh_dir("rbcflow_test_checkpoint_kill");
  const fs::path file = dir / "last.h5";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    for (long long k = 0;; ++k) {  // checkpoints as fast as it can, until killed
      CheckpointWriter w("f");
      w.put("k", k);
      w.put("data", Eigen::MatrixXd::Constant(300, 300, static_cast<double>(k)));
      w.write(file);
    }
  }
  while (!fs::exists(file)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  const Checkpoint c = Checkpoint::read(file, "f");
  const double k = static_cast<double>(c.integer("k"));
  EXPECT_EQ(c.matrix("data").minCoeff(), k);  // complete and self-consistent
  EXPECT_EQ(c.matrix("data").maxCoeff(), k);
  fs::remove_all(dir);
}
