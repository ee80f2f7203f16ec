#include "io/output_dir.h"

#include <unistd.h>

#include <system_error>

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

}  // namespace rbcflow
