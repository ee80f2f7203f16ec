#include "self_executable.h"

#include <unistd.h>

namespace rbcflow::cli {

std::string self_executable() {
  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return {};
  return std::string(self, std::size_t(n));
}

}  // namespace rbcflow::cli
