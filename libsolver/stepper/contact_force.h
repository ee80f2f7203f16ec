#pragma once
// Short-range repulsion between cell membranes and between a membrane and the vessel wall: an
// external force density on each membrane point within the range delta of another surface,
//
//   g(x) = sum over the surfaces S near x of  t(d_S(x)) n_S,   t(d) = kappa (delta - d)^2 / (delta d),
//
// d_S the point's distance from S and n_S the normal of S at its closest point (a cell's
// outward normal, the wall's into the lumen): a push away from S, zero with zero slope at
// d = delta, kappa / 2 at delta / 2, growing as kappa / d as the surfaces close (d is floored at
// delta / 20, where t = 18 kappa). It enters the membrane's balance as a body-force density
// does (eq. 23: the traction on the fluid is the membrane's minus g), so the flow that presses
// two surfaces together is met by a force, and the lubrication film between them drains at the
// rate that force allows. A short-range repulsion of this kind is what cellular blood-flow codes
// commonly add between membranes and walls; Lu, Rahimian & Zorin (J. Comput. Phys. 347, 2017)
// replace it by a constraint, at the price of a complementarity problem each step. The
// kinematic removal (collision.h, section 11.2 of the paper) alone holds a cell pressed on a
// wall at h_s with no force. With both, the repulsion acts over [h_s, delta] and the removal
// is the backstop below h_s. A cell's net repulsion is a load on the fluid: the stepper adds it
// to the mean pressure gradient (8) as it does a body force (docs/method-notes.md).
//
// t is minus the derivative of the potential phi(d) = kappa / delta [delta^2 ln(delta / d) - 2 delta
// (delta - d) + (delta^2 - d^2) / 2] per unit area (contact_potential); a sphere of radius R
// at gap g from a plane, rigid, feels 2 pi R phi(g) to O(delta / R) (Derjaguin's approximation
// of the integral of t over it).
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "geometry/contact/wall_distance.h"
#include "geometry/sph/sph_coeffs.h"
#include "geometry/sph/sph_transform.h"

namespace rbcflow {

struct ContactLaw {
  double range = 0.0;     // delta, units of a; 0: no repulsion
  double strength = 0.0;  // kappa, a traction (units of E_S / a: the shear modulus per length)
  bool active() const { return range > 0.0; }
  // t(d) above; 0 for d >= range.
  double traction(double separation) const;
};

// The potential per unit area of a membrane point at separation d, the integral of t from d to
// delta.
double contact_potential(const ContactLaw& law, double separation);

struct ContactReport {
  int cells_near_cells = 0;  // targets with a point within range of another cell (or an image of itself)
  int cells_near_wall = 0;   // targets with a point within range of the wall
  int cells_in_range = 0;    // targets with a point within range of either
  double max_traction = 0.0;  // the largest |g| at a grid point
  double min_separation = std::numeric_limits<double>::infinity();  // smallest d found in range
};

// The force density g on the grid points (of `grid_transform`) of the cells `targets` (indices
// into `cells`), stacked in that order (grid points x 3 each). The shapes of the targets and of
// every cell within the range of them must be held (held_shapes.h: a shape with no
// coefficients is a cell far from all the targets, and skipped). `period`: box sides of the
// periodic directions, 0 where not periodic. `wall` may be null. The report is of the targets.
Eigen::MatrixXd contact_force_density(const std::vector<SHCoeffs>& cells, const std::vector<int>& targets,
                                      const SHTransform& grid_transform, const Eigen::Vector3d& period,
                                      const WallDistance* wall, const ContactLaw& law, ContactReport& report);

}  // namespace rbcflow
