// The output directory: writability checked before a run (as a case error), folders made.
#include "io/output_dir.h"

#include <gtest/gtest.h>

#include <fstream>

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
