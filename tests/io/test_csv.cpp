// diagnostics.csv and cells.csv: the contract's header, empty fields, flushing, restarts.
#include "io/csv.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string first_line(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  return line;
}

DiagnosticsRow row(long step) {
  DiagnosticsRow r;
  r.step = step;
  r.time = 0.1 * step;
  r.dt = 0.1;
  r.mean_velocity = {0, 0, 5};
  r.pressure_gradient = {0, 0, -1.0 / 3.0};
  r.max_volume_error = 1e-7;
  r.gmres_cells = 12;
  r.seconds = 0.5;
  return r;
}

}  // namespace

TEST(Csv, DiagnosticsHeaderIsTheContract) {
  const fs::path dir = fresh_dir("rbcflow_test_csv_header");
  { DiagnosticsCsv d(dir / "diagnostics.csv"); }
  EXPECT_EQ(first_line(dir / "diagnostics.csv"),
            "step,time,dt,mean_velocity_x,mean_velocity_y,mean_velocity_z,pressure_gradient_x,"
            "pressure_gradient_y,pressure_gradient_z,effective_viscosity,tube_hematocrit,max_volume_error,"
            "max_area_error,gmres_cells,gmres_wall,wall_residual,seconds,collision_pairs,wall_contacts,"
            "collision_displacement,tube_velocity,pseudo_shear_rate_per_s,discharge_hematocrit,max_area_strain,"
            "cell_free_layer,min_wall_gap,max_volume_correction,max_contact_traction,contact_cells,"
            "max_area_strain_cell");
  { CellsCsv c(dir / "cells.csv"); }
  EXPECT_EQ(first_line(dir / "cells.csv"),
            "step,time,cell,centroid_x,centroid_y,centroid_z,velocity_x,velocity_y,velocity_z,volume,area,"
            "taylor_deformation,inclination");
  fs::remove_all(dir);
}

TEST(Csv, RowsAreFlushedExactAndEmptyWhereNotApplicable) {
  const fs::path dir = fresh_dir("rbcflow_test_csv_rows");
  DiagnosticsCsv d(dir / "diagnostics.csv");
  d.write(row(1));  // no tube, no wall
  DiagnosticsRow tube = row(2);
  tube.effective_viscosity = 1.7;
  tube.tube_hematocrit = 0.26;
  tube.gmres_wall = 30;
  tube.wall_residual = 1e-9;
  tube.collision_pairs = 3;
  tube.wall_contacts = 0;
  tube.collision_displacement = 0.0125;
  tube.tube_velocity = 2.5;
  tube.pseudo_shear_rate_per_s = 71.25;
  tube.discharge_hematocrit = 0.3125;
  tube.max_area_strain = 0.015625;
  tube.cell_free_layer = 0.375;
  tube.max_volume_correction = 3.0517578125e-05;
  d.write(tube);
  // Read while the writer is still open: the rows are on disk.
  const CsvTable t = read_csv(dir / "diagnostics.csv");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0][t.column("effective_viscosity")], "");
  EXPECT_EQ(t.rows[0][t.column("gmres_wall")], "");
  EXPECT_EQ(t.rows[0][t.column("wall_residual")], "");
  EXPECT_EQ(t.rows[0][t.column("collision_pairs")], "");
  EXPECT_EQ(t.rows[0][t.column("collision_displacement")], "");
  EXPECT_EQ(t.rows[1][t.column("effective_viscosity")], "1.7");
  EXPECT_EQ(t.rows[1][t.column("gmres_wall")], "30");
  EXPECT_EQ(t.rows[1][t.column("collision_pairs")], "3");
  EXPECT_EQ(t.rows[1][t.column("wall_contacts")], "0");
  EXPECT_EQ(t.rows[1][t.column("collision_displacement")], "0.0125");
  EXPECT_EQ(t.rows[0][t.column("tube_velocity")], "");
  EXPECT_EQ(t.rows[0][t.column("max_area_strain")], "");
  EXPECT_EQ(t.rows[1][t.column("tube_velocity")], "2.5");
  EXPECT_EQ(t.rows[1][t.column("pseudo_shear_rate_per_s")], "71.25");
  EXPECT_EQ(t.rows[1][t.column("discharge_hematocrit")], "0.3125");
  EXPECT_EQ(t.rows[1][t.column("max_area_strain")], "0.015625");
  EXPECT_EQ(t.rows[1][t.column("cell_free_layer")], "0.375");
  EXPECT_EQ(t.rows[0][t.column("max_volume_correction")], "");
  EXPECT_EQ(t.rows[1][t.column("max_volume_correction")], "3.0517578125e-05");
  EXPECT_EQ(std::strtod(t.rows[0][t.column("pressure_gradient_z")].c_str(), nullptr), -1.0 / 3.0);
  EXPECT_EQ(t.rows[1][t.column("step")], "2");

  CellsCsv c(dir / "cells.csv");
  CellRow a;
  a.step = 100;
  a.cell = 0;
  a.centroid = {1, 2, 3};
  CellRow b = a;
  b.cell = 1;
  b.inclination = 0.25;
  c.write({a, b});
  const CsvTable cells = read_csv(dir / "cells.csv");
  ASSERT_EQ(cells.rows.size(), 2u);
  EXPECT_EQ(cells.rows[1][cells.column("cell")], "1");
  EXPECT_EQ(cells.rows[1][cells.column("centroid_y")], "2");
  EXPECT_EQ(cells.rows[1][cells.column("inclination")], "0.25");
  fs::remove_all(dir);
}

TEST(Csv, RestartKeepsRowsUpToTheCheckpointAndAppends) {
  const fs::path dir = fresh_dir("rbcflow_test_csv_restart");
  const fs::path path = dir / "diagnostics.csv";
  {
    DiagnosticsCsv d(path);
    for (long s = 1; s <= 5; ++s) d.write(row(s));
  }
  std::ofstream(path, std::ios::app) << "6,0.6,0.1,0,0";  // a row cut short by a crash
  {
    DiagnosticsCsv d(path, 3);  // the last checkpoint was at step 3
    d.write(row(4));
  }
  const CsvTable t = read_csv(path);
  ASSERT_EQ(t.rows.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(t.rows[i][0], std::to_string(i + 1));
  // No file yet: a restart starts one.
  { DiagnosticsCsv d(dir / "new.csv", 3); }
  EXPECT_EQ(read_csv(dir / "new.csv").columns, diagnostics_columns());
  fs::remove_all(dir);
}

// A run written by an earlier version (the contract's first 20 columns, before the tube
// columns were added) continues: its rows are kept, padded with empty fields.
TEST(Csv, RestartContinuesAFileWithTheEarlierColumns) {
  const fs::path dir = fresh_dir("rbcflow_test_csv_earlier");
  const fs::path path = dir / "diagnostics.csv";
  std::vector<std::string> earlier(diagnostics_columns().begin(), diagnostics_columns().begin() + 20);
  ASSERT_EQ(earlier.back(), "collision_displacement");
  {
    CsvWriter w(path, earlier);
    for (int s = 1; s <= 3; ++s) w.write(std::vector<std::string>(20, std::to_string(s)));
  }
  {
    DiagnosticsCsv d(path, 2);
    DiagnosticsRow r = row(3);
    r.tube_velocity = 2.5;
    d.write(r);
  }
  const CsvTable t = read_csv(path);
  EXPECT_EQ(t.columns, diagnostics_columns());
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[1][t.column("collision_displacement")], "2");
  EXPECT_EQ(t.rows[1][t.column("tube_velocity")], "");
  EXPECT_EQ(t.rows[2][t.column("tube_velocity")], "2.5");
  // A header that is not a leading part of today's (a column renamed) is refused.
  earlier.back() = "collision_push";
  { CsvWriter w(dir / "renamed.csv", earlier); }
  EXPECT_THROW(DiagnosticsCsv(dir / "renamed.csv", 1), std::runtime_error);
  fs::remove_all(dir);
}

TEST(Csv, ForeignFileOnRestartAndUnwritablePathAreErrors) {
  const fs::path dir = fresh_dir("rbcflow_test_csv_errors");
  std::ofstream(dir / "diagnostics.csv") << "a,b,c\n1,2,3\n";
  EXPECT_THROW(DiagnosticsCsv(dir / "diagnostics.csv", 1), std::runtime_error);
  EXPECT_EQ(first_line(dir / "diagnostics.csv"), "a,b,c");  // left as it was
  try {
    DiagnosticsCsv d("/nonexistent-dir/diagnostics.csv");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/diagnostics.csv"), std::string::npos);
  }
  CsvWriter w(dir / "x.csv", {"a", "b"});
  EXPECT_THROW(w.write({"1"}), std::invalid_argument);
  EXPECT_THROW(read_csv(dir / "none.csv"), std::runtime_error);
  EXPECT_THROW(read_csv(dir / "x.csv").column("c"), std::runtime_error);
  fs::remove_all(dir);
}
