#include "thread_handover.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace rbcflow::cli {
namespace {

// The descriptor from the environment, made non-blocking; -1 when absent or not a pipe's end.
int handover_fd() {
  const char* text = std::getenv(kThreadsFdVariable);
  if (!text) return -1;
  char* end = nullptr;
  const long fd = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || fd < 0) return -1;
  const int flags = ::fcntl(static_cast<int>(fd), F_GETFL);
  if (flags < 0 || ::fcntl(static_cast<int>(fd), F_SETFL, flags | O_NONBLOCK) < 0) return -1;
  return static_cast<int>(fd);
}

}  // namespace

int threads_handed_over() {
  static const int fd = handover_fd();
  static std::string pending;  // a line not yet complete
  if (fd < 0) return 0;
  char buffer[64];
  ssize_t n;
  while ((n = ::read(fd, buffer, sizeof buffer)) > 0) pending.append(buffer, static_cast<std::size_t>(n));
  const std::size_t end = pending.rfind('\n');
  if (end == std::string::npos) return 0;
  const std::string complete = pending.substr(0, end);  // whole lines: only the last one counts
  pending.erase(0, end + 1);
  const std::size_t begin = complete.rfind('\n');
  const std::string line = begin == std::string::npos ? complete : complete.substr(begin + 1);
  const int threads = std::atoi(line.c_str());
  return threads > 0 ? threads : 0;
}

}  // namespace rbcflow::cli
