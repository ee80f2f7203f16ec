#pragma once
// Bad input the user must fix: a case file, a checkpoint, a mesh. The message names the file
// (and the line and key where there is one) and the reason. apps/ maps it to exit status 2;
// any other exception is a failure during a run (exit status 1).
#include <stdexcept>

namespace rbcflow {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An error in a case file: "FILE:LINE: key: reason (allowed: range)".
struct CaseError : InputError {
  using InputError::InputError;
};

}  // namespace rbcflow
