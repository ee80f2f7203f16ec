#pragma once
// Output is written atomically: to a temporary file beside the target, then renamed over it,
// so that an interrupted run never leaves a half-written file in place of a good one.
#include <filesystem>
#include <functional>

namespace rbcflow {

// Calls write(tmp) with a temporary path in the target's directory, then renames tmp to
// `target`. If write throws, the temporary is removed and `target` is untouched.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

}  // namespace rbcflow
