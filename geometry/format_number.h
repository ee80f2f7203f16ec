#pragma once
// A number for a message: printf's %g with `digits` significant digits ("3.5", "0.0125",
// "1e+04"), so that errors quote values as a user wrote or would read them.
#include <cstdio>
#include <string>

namespace rbcflow {

inline std::string format_number(double x, int digits = 4) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

}  // namespace rbcflow
