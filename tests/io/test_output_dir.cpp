// The output directory: writability checked before a run (as a case error), folders made.
#include "io/output_dir.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

const Case kCase = parse_case("[domain]\nbox = [4, 4, 4]\nmean_velocity = [0, 0, 1]\n[output]\ndir = \"x\"\n", "o.toml");

}  // namespace

TEST(OutputDir, WritableDirectoriesPassAndNothingIsCreated) {
  const fs::path base = fs::temp_directory_path() / "rbcflow_test_output_dir";
  fs::remove_all(base);
  fs::create_directories(base);
  EXPECT_NO_THROW(check_output_dir(kCase, base));
  EXPECT_NO_THROW(check_output_dir(kCase, base / "new" / "deeper"));
  EXPECT_FALSE(fs::exists(base / "new"));
  prepare_output_dir(base / "run");
  for (const char* d : {"vtk", "renders", "checkpoints"}) EXPECT_TRUE(fs::is_directory(base / "run" / d));
  fs::remove_all(base);
}

TEST(OutputDir, AFileInTheWayIsACaseErrorNamingTheKey) {
  const fs::path base = fs::temp_directory_path() / "rbcflow_test_output_file";
  fs::remove_all(base);
  fs::create_directories(base);
  std::ofstream(base / "file") << "x";
  try {
    check_output_dir(kCase, base / "file");
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()), "o.toml:5: output.dir: " + (base / "file").string() +
                                         " exists and is not a directory");
  }
  EXPECT_THROW(check_output_dir(kCase, base / "file" / "out"), CaseError);
  EXPECT_THROW(prepare_output_dir(base / "file" / "out"), std::runtime_error);
  fs::remove_all(base);
}

// A restart into a new directory starts its tables with the rows of the run that wrote the
// checkpoint; a restart in place, a checkpoint outside a run's checkpoints/ folder, or a
// directory with tables of its own take nothing, and the old run is left as it was.
TEST(OutputDir, ARestartElsewhereCarriesTheTablesOfTheCheckpointsRun) {
  const fs::path base = fs::temp_directory_path() / "rbcflow_test_carry_tables";
  fs::remove_all(base);
  prepare_output_dir(base / "run");
  std::ofstream(base / "run" / "checkpoints" / "step_00000002.h5") << "h5";
  std::ofstream(base / "run" / "diagnostics.csv") << "step,time\n1,0.1\n2,0.2\n3,0.3\n";
  std::ofstream(base / "run" / "cells.csv") << "step,cell\n1,0\n";
  std::ofstream(base / "run" / "branches.csv") << "step,branch\n1,0\n1,1\n";
  const fs::path checkpoint = base / "run" / "checkpoints" / "step_00000002.h5";
  const auto text = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };

  prepare_output_dir(base / "new");
  const auto run = carry_tables_from_checkpoint_run(checkpoint, base / "new");
  ASSERT_TRUE(run.has_value());
  EXPECT_TRUE(fs::equivalent(*run, base / "run"));
  EXPECT_EQ(text(base / "new" / "diagnostics.csv"), "step,time\n1,0.1\n2,0.2\n3,0.3\n");
  EXPECT_EQ(text(base / "new" / "cells.csv"), "step,cell\n1,0\n");
  EXPECT_EQ(text(base / "new" / "branches.csv"), "step,branch\n1,0\n1,1\n");

  std::ofstream(base / "new" / "diagnostics.csv") << "step,time\n1,0.1\n2,0.2\n";
  EXPECT_FALSE(carry_tables_from_checkpoint_run(checkpoint, base / "new").has_value());
  EXPECT_EQ(text(base / "new" / "diagnostics.csv"), "step,time\n1,0.1\n2,0.2\n");

  EXPECT_FALSE(carry_tables_from_checkpoint_run(checkpoint, base / "run").has_value());
  fs::copy_file(checkpoint, base / "loose.h5");
  prepare_output_dir(base / "other");
  EXPECT_FALSE(carry_tables_from_checkpoint_run(base / "loose.h5", base / "other").has_value());
  EXPECT_FALSE(fs::exists(base / "other" / "diagnostics.csv"));
  EXPECT_EQ(text(base / "run" / "diagnostics.csv"), "step,time\n1,0.1\n2,0.2\n3,0.3\n");
  fs::remove_all(base);
}

TEST(OutputDir, AnEarlierRunIsFoundByItsFilesAndClearedAlone) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_output_dir_earlier";
  fs::remove_all(dir);
  fs::create_directories(dir / "vtk");
  fs::create_directories(dir / "checkpoints");
  EXPECT_FALSE(holds_run(dir));  // empty folders are not a run
  std::ofstream(dir / "notes.txt") << "the user's own file";
  EXPECT_FALSE(holds_run(dir));
  std::ofstream(dir / "diagnostics.csv") << "step\n";
  std::ofstream(dir / "checkpoints" / "step_00000004.h5") << "x";
  EXPECT_TRUE(holds_run(dir));
  EXPECT_EQ(run_files(dir), (std::vector<std::string>{"diagnostics.csv", "checkpoints"}));
  clear_run(dir);
  EXPECT_FALSE(holds_run(dir));
  EXPECT_FALSE(fs::exists(dir / "checkpoints"));
  EXPECT_FALSE(fs::exists(dir / "vtk"));
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));  // not a run's file: kept
  fs::remove_all(dir);
}

TEST(OutputDir, ARestartInPlaceIsAStepOfTheSameRun) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_output_dir_in_place";
  fs::create_directories(dir / "checkpoints");
  EXPECT_TRUE(restarts_in_place(dir / "checkpoints" / "step_00000006.h5", dir));
  EXPECT_TRUE(restarts_in_place(dir / "checkpoints" / "step_00000006.h5", dir / "."));
  EXPECT_FALSE(restarts_in_place(dir / "step_00000006.h5", dir));  // not in a run's checkpoints/
  EXPECT_FALSE(restarts_in_place(dir / "checkpoints" / "step_00000006.h5", fs::temp_directory_path()));
  fs::remove_all(dir);
}
