// CellStepper::cells_for_output: the state of the cells a rank writes, brought from their
// holders (cell_stepper.h). The shapes are held by the ranks that moved the cells last
// (history_owners_, held_shapes.h), the membrane states and the rows of U^n and f^n by the
// step's owners (s.owners); each travels only to the ranks that name it.
#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

#include "libsolver/parallel/share_blocks.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow {

namespace {

std::span<double> span_of(auto& a) { return {a.data(), static_cast<std::size_t>(a.size())}; }

// A cell's output state as the arrays that travel: its membrane state, its rows of U^n and
// f^n (np x 3 each) and its shape.
struct CellPieces {
  MembraneState membrane;
  Eigen::MatrixXd velocity, traction;
  SHCoeffs shape;

  void size(int order, int np) {
    membrane.traction = SHCoeffs(order, 3);
    membrane.traction_grid.resize(np, 3);
    membrane.dilatation.resize(np);
    membrane.principal_tension.resize(np, 2);
    velocity.resize(np, 3);
    traction.resize(np, 3);
  }
  std::vector<std::span<double>> state() {
    return {span_of(membrane.traction.values()), span_of(membrane.traction_grid), span_of(membrane.dilatation),
            span_of(membrane.principal_tension), std::span<double>(&membrane.elastic_energy, 1), span_of(velocity),
            span_of(traction)};
  }
};

// Each cell's rank in `owners`.
std::vector<int> rank_of_cells(const CellOwners& owners, int ranks) {
  std::vector<int> rank(owners.order.size());
  for (int r = 0; r < ranks; ++r)
    for (int k = owners.first[r]; k < owners.first[r + 1]; ++k) rank[static_cast<std::size_t>(owners.order[k])] = r;
  return rank;
}

}  // namespace

CellsForOutput CellStepper::cells_for_output(const FlowSolution& s, std::vector<int> cells) const {
  const int nc = static_cast<int>(cells_.size());
  const int np = points_per_cell();
  const Communicator& ranks = options_.domain.ranks;
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  for (const int c : cells)
    if (c < 0 || c >= nc) throw std::invalid_argument("cells_for_output: no cell " + std::to_string(c));
  if (static_cast<int>(s.membrane.size()) != nc)
    throw std::invalid_argument("cells_for_output: not this stepper's solution");
  CellsForOutput out;
  out.cells = cells;
  if (nc == 0) return out;
  const int r = ranks.rank();
  const CellOwners& owners = s.owners;
  const int first = owners.first[r], end = owners.first[r + 1];
  const Eigen::MatrixXd velocity = owned_velocity(s);
  if (s.traction.rows() != velocity.rows()) throw std::invalid_argument("cells_for_output: not this stepper's solution");
  // The rank's own cells' pieces, and room for those it names of the others.
  std::vector<CellPieces> pieces(static_cast<std::size_t>(nc));
  std::vector<std::vector<std::span<double>>> states(static_cast<std::size_t>(nc)), shapes(static_cast<std::size_t>(nc));
  for (int k = first; k < end; ++k) {
    const int c = owners.order[k];
    CellPieces& p = pieces[static_cast<std::size_t>(c)];
    p.membrane = s.membrane[static_cast<std::size_t>(c)];
    p.velocity = velocity.middleRows(static_cast<Eigen::Index>(k - first) * np, np);
    p.traction = s.traction.middleRows(static_cast<Eigen::Index>(k - first) * np, np);
    states[static_cast<std::size_t>(c)] = p.state();
  }
  const std::vector<int> state_rank = rank_of_cells(owners, ranks.size());
  const std::vector<int> shape_rank = rank_of_cells(history_owners_, ranks.size());
  for (int k = history_owners_.first[r]; k < history_owners_.first[r + 1]; ++k) {
    const int c = history_owners_.order[k];
    CellPieces& p = pieces[static_cast<std::size_t>(c)];
    p.shape = cells_[static_cast<std::size_t>(c)].shape.coeffs();
    shapes[static_cast<std::size_t>(c)] = {span_of(p.shape.values())};
  }
  std::vector<int> state_needed, shape_needed;
  for (const int c : cells) {
    CellPieces& p = pieces[static_cast<std::size_t>(c)];
    const int order = cells_[static_cast<std::size_t>(c)].shape.order();
    if (state_rank[static_cast<std::size_t>(c)] != r) {
      p.size(order, np);
      states[static_cast<std::size_t>(c)] = p.state();
      state_needed.push_back(c);
    }
    if (shape_rank[static_cast<std::size_t>(c)] != r) {
      p.shape = SHCoeffs(order, 3);
      shapes[static_cast<std::size_t>(c)] = {span_of(p.shape.values())};
      shape_needed.push_back(c);
    }
  }
  bring_items(ranks, state_rank, state_needed, states);
  bring_items(ranks, shape_rank, shape_needed, shapes);
  out.velocity.resize(static_cast<Eigen::Index>(cells.size()) * np, 3);
  out.traction.resize(out.velocity.rows(), 3);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    CellPieces& p = pieces[static_cast<std::size_t>(cells[i])];
    out.shapes.emplace_back(std::move(p.shape));
    out.membranes.push_back(std::move(p.membrane));
    out.velocity.middleRows(static_cast<Eigen::Index>(i) * np, np) = p.velocity;
    out.traction.middleRows(static_cast<Eigen::Index>(i) * np, np) = p.traction;
  }
  return out;
}

}  // namespace rbcflow
