#pragma once
// Output is written atomically: to a temporary file beside the target, then renamed over it,
// so that an interrupted run never leaves a half-written file in place of a good one.
#include <filesystem>
#include <functional>
#include <string>

namespace rbcflow {

// DIR/.NAME.tmp.TAG for the target DIR/NAME: where its content is written before the rename.
std::filesystem::path temporary_beside(const std::filesystem::path& target, const std::string& tag);

// Calls write(tmp) with a temporary path in the target's directory, then renames tmp to
// `target`. If write throws, the temporary is removed and `target` is untouched.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

}  // namespace rbcflow
