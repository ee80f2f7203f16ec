#include "io/output_dir.h"

#include <unistd.h>

#include <system_error>

#include "io/atomic_file.h"

namespace rbcflow {

namespace fs = std::filesystem;

void check_output_dir(const Case& c, const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw case_error(c, "output.dir", dir.string() + " exists and is not a directory");
  }
  fs::path existing = fs::absolute(dir, ec);
  while (!fs::exists(existing, ec) && existing.has_relative_path()) existing = existing.parent_path();
  if (!fs::is_directory(existing, ec) || ::access(existing.c_str(), W_OK | X_OK) != 0) {
    throw case_error(c, "output.dir", "cannot write " + dir.string() + " (" + existing.string() +
                                          " is not a writable directory)");
  }
}

namespace {

constexpr const char* kRunFiles[] = {"case.toml",    "diagnostics.csv", "cells.csv", "branches.csv",
                                     "rbcflow.xdmf", "rbcflow.h5",      "rbcflow.pvd", "diagnostics.png",
                                     "vtk",          "renders",         "checkpoints"};

}  // namespace

std::vector<std::string> run_files(const fs::path& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const char* name : kRunFiles) {
    const fs::path p = dir / name;
    if (fs::is_directory(p, ec) ? !fs::is_empty(p, ec) : fs::exists(p, ec)) found.emplace_back(name);
  }
  return found;
}

bool holds_run(const fs::path& dir) { return !run_files(dir).empty(); }

void clear_run(const fs::path& dir) {
  for (const char* name : kRunFiles) {
    std::error_code ec;
    fs::remove_all(dir / name, ec);
    if (ec) throw std::runtime_error("cannot remove " + (dir / name).string() + " of the earlier run: " + ec.message());
  }
}

void prepare_output_dir(const fs::path& dir) {
  for (const fs::path& d : {dir, dir / "vtk", dir / "renders", dir / "checkpoints"}) {
    std::error_code ec;
    fs::create_directories(d, ec);
    if (ec || !fs::is_directory(d)) {
      throw std::runtime_error("cannot create the output folder " + d.string() +
                               (ec ? ": " + ec.message() : std::string()));
    }
  }
}

std::optional<fs::path> run_of_checkpoint(const fs::path& checkpoint) {
  const fs::path folder = checkpoint.parent_path();
  if (folder.filename() != "checkpoints") return std::nullopt;
  return folder.parent_path().empty() ? fs::path(".") : folder.parent_path();
}

bool restarts_in_place(const fs::path& checkpoint, const fs::path& dir) {
  const auto run = run_of_checkpoint(checkpoint);
  std::error_code ec;
  return run && fs::is_directory(dir, ec) && fs::equivalent(*run, dir, ec) && !ec;
}

std::optional<fs::path> carry_tables_from_checkpoint_run(const fs::path& checkpoint, const fs::path& dir) {
  const auto found = run_of_checkpoint(checkpoint);
  if (!found) return std::nullopt;
  const fs::path& run = *found;
  std::error_code ec;
  if (!fs::is_directory(run, ec) || fs::equivalent(run, dir, ec) || ec) return std::nullopt;
  bool copied = false;
  for (const char* table : {"diagnostics.csv", "cells.csv", "branches.csv"}) {
    const fs::path from = run / table, to = dir / table;
    if (!fs::is_regular_file(from, ec) || fs::exists(to, ec)) continue;
    write_atomically(to, [&](const fs::path& tmp) {
      fs::copy_file(from, tmp, fs::copy_options::overwrite_existing);
    });
    copied = true;
  }
  return copied ? std::optional<fs::path>(run) : std::nullopt;
}

}  // namespace rbcflow
