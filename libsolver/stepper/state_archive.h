#pragma once
// A checkpoint as the stepper sees it: named items (names may hold '/' for groups), written or
// read through one list of them, so that each piece of state names its items once and a new
// field is one line beside the others (StepperState::archive). The file format is the caller's
// (scenario/checkpoint.h writes HDF5); libsolver knows no files.
#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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
  // Cell numbers; written only when not empty, read as empty when absent.
  virtual void indices(const std::string& name, std::vector<int>& x) = 0;

  // Reading: a matrix item's (rows, columns), (0, 0) where absent, and its rows
  // [first, first + count), so that a rank reads only its part of the state (CellStepper::load
  // on several ranks). The defaults read the whole matrix.
  virtual std::pair<long long, long long> matrix_size(const std::string& name) {
    Eigen::MatrixXd m;
    matrix(name, m, false);
    return {m.rows(), m.cols()};
  }
  virtual Eigen::MatrixXd rows(const std::string& name, long long first, long long count) {
    Eigen::MatrixXd m;
    matrix(name, m, true);
    if (first < 0 || count < 0 || first + count > m.rows())
      throw std::invalid_argument(name + " has " + std::to_string(m.rows()) + " rows, not rows " +
                                  std::to_string(first) + " to " + std::to_string(first + count));
    return m.middleRows(first, count);
  }

  // Writing on several ranks: whether the archive takes a matrix from the ranks' parts of its
  // rows (part()), each rank giving those it holds, so that no rank gathers the whole state
  // (CellStepper::save). Otherwise every rank gives every item whole.
  virtual bool takes_parts() const { return false; }
  // Writing: the rows [first_row, first_row + rows.rows()) of a matrix of `total_rows` rows;
  // every rank names every such matrix, with its own rows (possibly none). Where the archive
  // takes no parts they must be the whole matrix.
  virtual void part(const std::string& name, long long total_rows, long long first_row, const Eigen::MatrixXd& rows) {
    if (first_row != 0 || rows.rows() != total_rows)
      throw std::logic_error(name + ": a part of a matrix given to an archive that takes whole matrices");
    Eigen::MatrixXd whole = rows;
    matrix(name, whole, true);
  }
};

}  // namespace rbcflow
