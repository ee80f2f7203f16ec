#include "scenario/checkpoint.h"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "io/output_dir.h"
#include "libsolver/parallel/ownership.h"
#include "scenario/shared_output.h"

namespace rbcflow {
namespace {

class CheckpointOut : public StateArchive {
 public:
  explicit CheckpointOut(CheckpointWriter& w) : w_(w) {}
  bool reading() const override { return false; }
  void real(const std::string& name, double& x) override { w_.put(name, x); }
  void integer(const std::string& name, long& x) override { w_.put(name, static_cast<long long>(x)); }
  void matrix(const std::string& name, Eigen::MatrixXd& x, bool required) override {
    if (required || x.size()) w_.put(name, x);
  }

 private:
  CheckpointWriter& w_;
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
    x = required || k_.has(name) ? k_.matrix(name) : Eigen::MatrixXd();
  }

 private:
  const Checkpoint& k_;
};

// Which rows of a checkpoint item this rank writes: the items of one cell ("cells/K/...") are
// its owner's, any other as rows_to_write says (shared_output.h).
std::pair<long long, long long> item_rows(const std::string& name, long long rows, long cells,
                                          const Communicator& ranks) {
  if (name.rfind("cells/", 0) == 0 && cells > 0) {
    const std::string rest = name.substr(6);
    const std::size_t slash = rest.find('/');
    if (slash != std::string::npos && slash > 0 && rest.find_first_not_of("0123456789") == slash) {
      const bool mine = owned_block(static_cast<int>(cells), ranks).contains(std::stoi(rest.substr(0, slash)));
      return mine ? std::pair{0LL, rows} : std::pair{0LL, 0LL};
    }
  }
  return rows_to_write(rows, cells, ranks);
}

}  // namespace

void write_checkpoint(const CellStepper& stepper, const Case& c, const std::filesystem::path& file,
                      const Communicator& ranks) {
  CheckpointWriter w(case_fingerprint(c));
  w.put("state_version", static_cast<long long>(kCheckpointStateVersion));
  w.put("case", case_toml(c));
  CheckpointOut out(w);
  stepper.save(out);
  if (ranks.size() == 1 || !CheckpointWriter::shared_by_ranks()) {
    if (ranks.root()) w.write(file);
    return;
  }
  const long cells = static_cast<long>(stepper.cells().size());
  const long tag = ranks.sum(ranks.root() ? static_cast<long>(::getpid()) : 0L);  // rank 0's process id
  w.write(file, {ranks.mpi_handle(), ranks.rank(), std::to_string(tag),
                 [&](const std::string& name, long long rows) { return item_rows(name, rows, cells, ranks); }});
}

void read_checkpoint(CellStepper& stepper, const Case& c, const std::filesystem::path& file) {
  const Case run = as_run_of_checkpoint(c, file);
  const Checkpoint k = Checkpoint::read(file, case_fingerprint(run));
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

}  // namespace rbcflow
