#pragma once
// HDF5 checkpoints: named double and integer matrices, integers, reals and strings in one
// file, written atomically (a temporary beside the target, synced, then renamed) so that a
// run killed at any moment leaves the last good checkpoint. Names may contain '/' (groups):
// "cells/0/coefficients". Every stateful object of the stepper writes its own items.
//
// The file carries the case fingerprint (case_fingerprint in io/case.h); a checkpoint of
// another case is rejected with a clear message.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "io/input_error.h"

namespace rbcflow {

// A checkpoint that cannot be used: missing, truncated, foreign, or of another case (exit 2).
struct CheckpointError : InputError {
  using InputError::InputError;
};

class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::string case_fingerprint);

  // Adds an item; a name given twice is an error (std::invalid_argument). Matrices hold
  // doubles or ints (any Eigen expression of them).
  template <typename Derived>
  void put(const std::string& name, const Eigen::MatrixBase<Derived>& m) {
    using Scalar = typename Derived::Scalar;
    static_assert(std::is_same_v<Scalar, double> || std::is_same_v<Scalar, int>,
                  "checkpoint matrices hold doubles or ints");
    if constexpr (std::is_same_v<Scalar, double>) {
      add(name, Eigen::MatrixXd(m));
    } else {
      add(name, Eigen::MatrixXi(m));
    }
  }
  // The rows [first_row, first_row + rows.rows()) of a matrix of `total_rows` rows, whose other
  // rows the other ranks give (write(file, ranks)); in a file of one process, every row.
  void put_rows(const std::string& name, long long total_rows, long long first_row, const Eigen::MatrixXd& rows);
  void put(const std::string& name, long long value);
  void put(const std::string& name, double value);
  void put(const std::string& name, const std::string& value);

  // Writes every item to `file` atomically; throws std::runtime_error naming the file (and
  // leaves an earlier file there untouched) when it cannot.
  void write(const std::filesystem::path& file) const;

  // The ranks of a run writing one checkpoint together (parallel HDF5: io/hdf5_file.h). Each
  // names every item; `rows` says which rows of a whole item (its name and row count) this rank
  // writes, an item of put_rows its own rows, and the ranks' rows must cover every item once. `tag` names the temporary file,
  // the same on every rank. Rank 0 makes the finished file the checkpoint.
  struct Ranks {
    int mpi_handle = -1;
    int rank = 0;
    std::string tag;
    std::function<std::pair<long long, long long>(const std::string& name, long long rows)> rows;
  };
  // The same written by the ranks together; every rank calls it with the same file. Only in
  // a build with parallel HDF5: shared_by_ranks().
  void write(const std::filesystem::path& file, const Ranks& ranks) const;
  static bool shared_by_ranks();

 private:
  struct Rows {  // put_rows
    Eigen::MatrixXd rows;
    long long first = 0, total = 0;
  };
  using Item = std::variant<Eigen::MatrixXd, Eigen::MatrixXi, Rows, long long, double, std::string>;
  void add(const std::string& name, Item item);
  // Every item into the open file `f`; with `ranks`, each of this rank's rows.
  void write_items(std::int64_t f, const Ranks* ranks) const;  // f: the file's hid_t
  std::string fingerprint_;
  std::map<std::string, Item> items_;
};

class Checkpoint {
 public:
  // Reads every item of `file`. Throws CheckpointError when the file is missing, is not an
  // HDF5 file or is truncated, is not an rbcflow checkpoint, or carries another fingerprint.
  // The matrices of reals that `by_rows` names are not read: the file stays open while the
  // Checkpoint lives, and rows() reads the rows asked for (a rank of a run its own cells').
  static Checkpoint read(const std::filesystem::path& file, const std::string& case_fingerprint,
                         const std::function<bool(const std::string& name)>& by_rows = {});
  // The same without the fingerprint check: to find out which case a checkpoint belongs to.
  static Checkpoint read_any_case(const std::filesystem::path& file);

  bool has(const std::string& name) const { return items_.count(name) > 0; }
  std::vector<std::string> names() const;
  // The item `name` of that type; CheckpointError naming the file and item otherwise.
  const Eigen::MatrixXd& matrix(const std::string& name) const;
  const Eigen::MatrixXi& int_matrix(const std::string& name) const;
  // A matrix of reals read whole or by rows: its (rows, columns), and its rows
  // [first, first + count). matrix() of an item read by rows throws CheckpointError.
  std::pair<long long, long long> matrix_size(const std::string& name) const;
  Eigen::MatrixXd rows(const std::string& name, long long first, long long count) const;
  long long integer(const std::string& name) const;
  double real(const std::string& name) const;
  const std::string& text(const std::string& name) const;

 private:
  struct ByRows {  // a matrix of reals left in the file
    long long rows = 0, cols = 0;
  };
  struct OpenFile;  // the file, open while an item is left in it
  using Item = std::variant<Eigen::MatrixXd, Eigen::MatrixXi, ByRows, long long, double, std::string>;
  static Checkpoint read_checked(const std::filesystem::path& file, const std::string* case_fingerprint,
                                 const std::function<bool(const std::string& name)>& by_rows);
  template <typename T>
  const T& get(const std::string& name, const char* what) const;
  std::filesystem::path file_;
  std::map<std::string, Item> items_;
  std::shared_ptr<const OpenFile> open_;
};

}  // namespace rbcflow
