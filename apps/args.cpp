#include <algorithm>
#include <limits>

#include "cli.h"

namespace rbcflow::cli {

long positive_integer(const std::string& command, const std::string& option, const std::string& text, long max) {
  std::size_t used = 0;
  long v = -1;
  try {
    v = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || v < 1 || v > max) {
    const std::string range = max == std::numeric_limits<long>::max() ? "a positive integer"
                                                                       : "an integer from 1 to " + std::to_string(max);
    throw UsageError("rbcflow " + command + ": " + option + " must be " + range + ", got '" + text + "'");
  }
  return v;
}

Args::Args(std::string command, std::vector<std::string> args)
    : command_(std::move(command)), args_(std::move(args)) {}

bool Args::flag(const std::string& name) {
  auto it = std::find(args_.begin(), args_.end(), name);
  if (it == args_.end()) return false;
  args_.erase(it);
  return true;
}

bool Args::option(const std::string& name, std::string& v) {
  auto it = std::find(args_.begin(), args_.end(), name);
  if (it == args_.end()) return false;
  if (it + 1 == args_.end()) throw UsageError("rbcflow " + command_ + ": " + name + " needs a value");
  v = *(it + 1);
  args_.erase(it, it + 2);
  return true;
}

std::string Args::positional(const std::string& what) {
  auto it = std::find_if(args_.begin(), args_.end(), [](const std::string& a) {
    return a.empty() || a[0] != '-';
  });
  if (it == args_.end()) throw UsageError("rbcflow " + command_ + ": missing " + what);
  std::string v = *it;
  args_.erase(it);
  return v;
}

std::string Args::next_positional() {
  auto it = std::find_if(args_.begin(), args_.end(), [](const std::string& a) { return !a.empty() && a[0] != '-'; });
  if (it == args_.end()) return {};
  std::string v = *it;
  args_.erase(it);
  return v;
}

bool Args::help_requested() const {
  return std::find_if(args_.begin(), args_.end(), [](const std::string& a) {
           return a == "--help" || a == "-h";
         }) != args_.end();
}

void Args::finish() const {
  if (!args_.empty()) throw UsageError("rbcflow " + command_ + ": unexpected argument '" + args_.front() + "'");
}

}  // namespace rbcflow::cli
