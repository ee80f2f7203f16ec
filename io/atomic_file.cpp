#include "atomic_file.h"

#include <unistd.h>

#include <stdexcept>
#include <string>

namespace rbcflow {

std::filesystem::path temporary_beside(const std::filesystem::path& target, const std::string& tag) {
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  // Built with append, not operator+: GCC 12 raises a false -Wrestrict on "." + string.
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp.").append(tag);
  return dir / name;
}

void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write) {
  namespace fs = std::filesystem;
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) {
    throw std::runtime_error("cannot write " + target.string() + ": directory " + dir.string() +
                             " does not exist");
  }
  const fs::path tmp = temporary_beside(target, std::to_string(::getpid()));
  try {
    write(tmp);
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

}  // namespace rbcflow
