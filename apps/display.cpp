#include "display.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/render.h"
#include "self_executable.h"

namespace rbcflow::cli {

void ensure_display() {
  if (display_available()) return;
  if (std::getenv("RBCFLOW_UNDER_XVFB")) {
    throw std::runtime_error("xvfb-run started no X display (DISPLAY is still unset)");
  }
  // This process's own command line, to run it again.
  const std::string self = self_executable();
  std::ifstream cmdline("/proc/self/cmdline", std::ios::binary);
  const std::string all((std::istreambuf_iterator<char>(cmdline)), std::istreambuf_iterator<char>());
  if (self.empty() || all.empty()) {
    throw std::runtime_error("no X display, and cannot find this command line to run it under xvfb-run");
  }
  std::vector<std::string> argv;
  for (std::size_t start = 0; start < all.size();) {
    const std::size_t end = all.find('\0', start);
    argv.push_back(all.substr(start, end - start));
    start = end == std::string::npos ? all.size() : end + 1;
  }
  std::vector<const char*> args = {"xvfb-run", "-a", "-s", "-screen 0 1280x1024x24 -noreset", self.c_str()};
  for (std::size_t i = 1; i < argv.size(); ++i) args.push_back(argv[i].c_str());
  args.push_back(nullptr);
  ::setenv("RBCFLOW_UNDER_XVFB", "1", 1);
  std::fprintf(stderr, "rbcflow: no X display; rendering on a virtual one (xvfb-run)\n");
  std::fflush(stderr);
  std::fflush(stdout);
  ::execvp("xvfb-run", const_cast<char* const*>(args.data()));
  throw std::runtime_error(std::string("no X display, and xvfb-run cannot be started (") + std::strerror(errno) +
                           "): install it (apt-get install xvfb xauth) or set DISPLAY");
}

}  // namespace rbcflow::cli
