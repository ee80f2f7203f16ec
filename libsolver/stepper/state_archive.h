#pragma once
// A checkpoint as the stepper sees it: named items (names may hold '/' for groups), written or
// read through one list of them, so that each piece of state names its items once and a new
// field is one line beside the others (StepperState::archive). The file format is the caller's
// (scenario/checkpoint.h writes HDF5); libsolver knows no files.
#include <Eigen/Core>
#include <string>

namespace rbcflow {

class StateArchive {
 public:
  virtual ~StateArchive() = default;
  virtual bool reading() const = 0;
  // Writing stores the value; reading sets it from the item, and throws (naming the item) when
  // it is absent. A matrix that is not `required` is written only when it is not empty and
  // read as empty when absent.
  virtual void real(const std::string& name, double& x) = 0;
  virtual void integer(const std::string& name, long& x) = 0;
  virtual void matrix(const std::string& name, Eigen::MatrixXd& x, bool required) = 0;
};

}  // namespace rbcflow
