#pragma once
// The path of this running program (/proc/self/exe), to start it again: study's child runs and
// the re-run under xvfb-run. Empty when it cannot be read.
#include <string>

namespace rbcflow::cli {

std::string self_executable();

}  // namespace rbcflow::cli
