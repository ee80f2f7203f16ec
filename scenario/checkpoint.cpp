#include "scenario/checkpoint.h"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "io/output_dir.h"
#include "scenario/shared_output.h"

namespace rbcflow {
namespace {

// `parts`: the ranks write the file together (parallel HDF5), each from its part of the state.
class CheckpointOut : public StateArchive {
 public:
  CheckpointOut(CheckpointWriter& w, bool parts) : w_(w), parts_(parts) {}
  bool reading() const override { return false; }
  void real(const std::string& name, double& x) override { w_.put(name, x); }
  void integer(const std::string& name, long& x) override { w_.put(name, static_cast<long long>(x)); }
  void matrix(const std::string& name, Eigen::MatrixXd& x, bool required) override {
    if (required || x.size()) w_.put(name, x);
  }
  void indices(const std::string& name, std::vector<int>& x) override {
    if (!x.empty()) w_.put(name, Eigen::Map<const Eigen::VectorXi>(x.data(), static_cast<Eigen::Index>(x.size())));
  }
  bool takes_parts() const override { return parts_; }
  void part(const std::string& name, long long total_rows, long long first_row, const Eigen::MatrixXd& rows) override {
    if (parts_) {
      w_.put_rows(name, total_rows, first_row, rows);
    } else {
      StateArchive::part(name, total_rows, first_row, rows);
    }
  }

 private:
  CheckpointWriter& w_;
  bool parts_;
};

// Checkpoint's accessors throw CheckpointError naming the file and the item for what is
// absent or of another type.
class CheckpointIn : public StateArchive {
 public:
  explicit CheckpointIn(const Checkpoint& k) : k_(k) {}
  bool reading() const override { return true; }
  void real(const std::string& name, double& x) override { x = k_.real(name); }
  void integer(const std::string& name, long& x) override { x = static_cast<long>(k_.integer(name)); }
  void matrix(const std::string& name, Eigen::MatrixXd& x, bool required) override {
    x = required || k_.has(name) ? k_.rows(name, 0, k_.matrix_size(name).first) : Eigen::MatrixXd();
  }
  std::pair<long long, long long> matrix_size(const std::string& name) override {
    return k_.has(name) ? k_.matrix_size(name) : std::pair<long long, long long>{0, 0};
  }
  Eigen::MatrixXd rows(const std::string& name, long long first, long long count) override {
    return k_.rows(name, first, count);
  }
  void indices(const std::string& name, std::vector<int>& x) override {
    x.clear();
    if (!k_.has(name)) return;
    const Eigen::MatrixXi& m = k_.int_matrix(name);
    x.assign(m.data(), m.data() + m.size());
  }

 private:
  const Checkpoint& k_;
};

}  // namespace

void write_checkpoint(const CellStepper& stepper, const Case& c, const std::filesystem::path& file,
                      const Communicator& ranks) {
  CheckpointWriter w(case_fingerprint(c));
  w.put("state_version", static_cast<long long>(kCheckpointStateVersion));
  w.put("case", case_toml(c));
  const bool together = ranks.size() > 1 && CheckpointWriter::shared_by_ranks();
  CheckpointOut out(w, together);
  stepper.save(out);  // collective on several ranks
  if (!together) {
    if (ranks.root()) w.write(file);
    return;
  }
  const long cells = static_cast<long>(stepper.cells().size());
  const long tag = ranks.sum(ranks.root() ? static_cast<long>(::getpid()) : 0L);  // rank 0's process id
  w.write(file, {ranks.mpi_handle(), ranks.rank(), std::to_string(tag),
                 [&](const std::string&, long long rows) { return rows_to_write(rows, cells, ranks); }});
}

void read_checkpoint(CellStepper& stepper, const Case& c, const std::filesystem::path& file) {
  const Case run = as_run_of_checkpoint(c, file);
  // The cells' coefficients and velocities are read by rows: on several ranks each rank reads
  // its own cells' alone (CellStepper::load).
  const Checkpoint k = Checkpoint::read(file, case_fingerprint(run), [](const std::string& name) {
    return name.starts_with("cells/") && (name.ends_with("/coefficients") || name.ends_with("_velocity"));
  });
  const long long version = k.has("state_version") ? k.integer("state_version") : 1;
  if (version < 1 || version > kCheckpointStateVersion) {
    throw CheckpointError(file.string() + ": checkpoint state version " + std::to_string(version) +
                          "; this rbcflow reads state versions 1 to " + std::to_string(kCheckpointStateVersion) +
                          " (written by a newer rbcflow?)");
  }
  CheckpointIn in(k);
  try {
    if (rediscretised_keys(run, c).empty()) {
      stepper.load(in);
    } else {
      stepper.load_rediscretised(in);
    }
  } catch (const std::invalid_argument& e) {
    throw CheckpointError(file.string() + ": " + e.what());
  }
}

Case case_of_checkpoint(const std::filesystem::path& file) {
  const Checkpoint k = Checkpoint::read_any_case(file);
  if (k.has("case")) return parse_case(k.text("case"), file.string() + " (its case)");
  if (const auto run = run_of_checkpoint(file); run && std::filesystem::is_regular_file(*run / "case.toml")) {
    return read_case(*run / "case.toml");
  }
  throw CheckpointError(file.string() + ": holds no case, and is not in a run's checkpoints/ folder beside its "
                        "case.toml");
}

Case as_run_of_checkpoint(const Case& c, const std::filesystem::path& file) {
  Case run = c;
  try {
    const Case before = case_of_checkpoint(file);
    if (run.cells && before.cells) {
      run.cells->order = before.cells->order;
      run.cells->dealias = before.cells->dealias;
    }
    run.time.dt = before.time.dt;
    run.time.dt_safety = before.time.dt_safety;
    run.time.contact_range = before.time.contact_range;
    run.time.contact_strength = before.time.contact_strength;
  } catch (const std::exception&) {
    return c;  // no case to read: the fingerprint check names the file
  }
  return run;
}

std::vector<std::string> rediscretised_keys(const Case& run, const Case& c) {
  std::vector<std::string> changed;
  const auto note = [&](const std::string& key, const std::string& before, const std::string& now) {
    if (before != now) changed.push_back(key + " " + before + " -> " + now);
  };
  const auto number = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return std::string(buf);
  };
  if (run.cells && c.cells) {
    note("cells.order", std::to_string(run.cells->order), std::to_string(c.cells->order));
    note("cells.dealias", std::to_string(run.cells->dealias), std::to_string(c.cells->dealias));
  }
  note("time.dt", run.time.dt ? number(*run.time.dt) : "\"auto\"", c.time.dt ? number(*c.time.dt) : "\"auto\"");
  if (!run.time.dt && !c.time.dt) note("time.dt_safety", number(run.time.dt_safety), number(c.time.dt_safety));
  return changed;
}

std::vector<std::string> contact_keys(const Case& run, const Case& c) {
  std::vector<std::string> changed;
  const auto note = [&](const std::string& key, double before, double now) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s %.6g -> %.6g", key.c_str(), before, now);
    if (before != now) changed.push_back(buf);
  };
  note("time.contact_range", run.time.contact_range, c.time.contact_range);
  note("time.contact_strength", run.time.contact_strength, c.time.contact_strength);
  return changed;
}

}  // namespace rbcflow
