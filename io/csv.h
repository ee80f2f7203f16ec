#pragma once
// diagnostics.csv and cells.csv (docs/case-format.md): the contract's columns in order, one row
// per step and one row per cell per frame, appended and flushed as written so that a crash
// loses at most the row being written. Empty fields where a value does not apply.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/case.h"

namespace rbcflow {

struct DiagnosticsRow {
  long step = 0;
  double time = 0;
  double dt = 0;
  Vec3 mean_velocity{};
  Vec3 pressure_gradient{};
  std::optional<double> effective_viscosity;  // (46) with (45); empty without a tube
  std::optional<double> tube_hematocrit;      // empty without a vessel or cells
  double max_volume_error = 0;                // relative to each cell's initial volume
  double max_area_error = 0;
  int gmres_cells = 0;
  std::optional<int> gmres_wall;        // empty without a wall
  std::optional<double> wall_residual;  // empty without a wall
  double seconds = 0;                   // wall-clock time of the step
  // Collision removal (section 11.2); empty when it is off (h_s = 0).
  std::optional<int> collision_pairs;             // cell pairs closer than h_s, periodic images included
  std::optional<int> wall_contacts;               // cells closer than h_s to the wall
  std::optional<double> collision_displacement;   // largest push of a grid point
  // A tube or constriction: its mean velocity U, U / D in 1/s ([units]), the discharge
  // hematocrit (cells' volume flux over the tube's, with cells); with cells, the largest local
  // area strain |J_S - 1| of the membranes.
  std::optional<double> tube_velocity;
  std::optional<double> pseudo_shear_rate_per_s;
  std::optional<double> discharge_hematocrit;
  std::optional<double> max_area_strain;
  std::optional<double> cell_free_layer;  // a tube or constriction with cells (cell_free_layer.h)
  std::optional<double> min_wall_gap;     // a wall and cells: closest approach of a cell to it
  std::optional<double> max_volume_correction;  // the volume constraint's largest restoration (cells and the constraint)
  // The contact repulsion (cells and time.contact_range > 0): the largest force density it put
  // on a membrane point, and the cells with a point within its range of another cell or the wall.
  std::optional<double> max_contact_traction;
  std::optional<int> contact_cells;
  std::optional<int> max_area_strain_cell;  // with cells: the cell of max_area_strain
};

struct CellRow {
  long step = 0;
  double time = 0;
  int cell = 0;
  Vec3 centroid{};
  Vec3 velocity{};  // area-weighted mean surface velocity
  double volume = 0;
  double area = 0;
  double taylor_deformation = 0;  // (L - B) / (L + B) of the inertia ellipsoid
  double inclination = 0;         // long axis to the flow direction, radians
};

// One branch of the vessel after a step (branches.csv).
struct BranchRow {
  long step = 0;
  double time = 0;
  int branch = 0;
  double flow_rate = 0;   // volume flux through its mid cross-section, along the branch
  int cells = 0;          // cells whose centroid is in the branch
  long cells_passed = 0;  // centroids that crossed the mid-section along the branch, less those back
};

const std::vector<std::string>& diagnostics_columns();
const std::vector<std::string>& cells_columns();
const std::vector<std::string>& branches_columns();

// A CSV file written row by row. A new file starts with the header. On a restart from step
// S (resume_step = S), an existing file keeps its rows with step <= S (a run that went past
// its last checkpoint leaves later rows; they are dropped) and new rows are appended; its
// header must be `columns`.
class CsvWriter {
 public:
  CsvWriter(std::filesystem::path path, std::vector<std::string> columns,
            std::optional<long> resume_step = std::nullopt);
  // One row: as many fields as columns; each field already formatted (may be empty).
  void write(const std::vector<std::string>& fields);
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::size_t columns_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
};

class DiagnosticsCsv {
 public:
  explicit DiagnosticsCsv(const std::filesystem::path& path, std::optional<long> resume_step = std::nullopt);
  void write(const DiagnosticsRow& row);

 private:
  CsvWriter csv_;
};

class CellsCsv {
 public:
  explicit CellsCsv(const std::filesystem::path& path, std::optional<long> resume_step = std::nullopt);
  void write(const std::vector<CellRow>& frame);  // one row per cell

 private:
  CsvWriter csv_;
};

class BranchesCsv {
 public:
  explicit BranchesCsv(const std::filesystem::path& path, std::optional<long> resume_step = std::nullopt);
  void write(const std::vector<BranchRow>& rows);  // one row per branch

 private:
  CsvWriter csv_;
};

// A CSV file read back: the header and the rows as text (for plots and tests).
struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  // Index of a column; throws std::runtime_error naming the file when it is absent.
  std::size_t column(const std::string& name) const;
  std::filesystem::path path;
};
CsvTable read_csv(const std::filesystem::path& path);

// The shortest text that reads back as the same double (empty for an empty optional).
std::string csv_number(double x);
std::string csv_number(const std::optional<double>& x);

}  // namespace rbcflow
