#pragma once
// A viscous gravity current: a heavy, very viscous fluid spreading over a
// rigid floor, slow and thin enough for lubrication theory. Huppert 1982,
// "The propagation of two-dimensional and axisymmetric viscous gravity
// currents over a rigid horizontal surface", J. Fluid Mech. 121: 43-58.

#include "analysis/particle_frames.hpp"

namespace sph {

// Huppert's similarity solution in 2D (eq. 2.14): a current of area A per
// unit width spreading from a wall reaches
//   x_N(t) = 1.411 (g A^3 t / (3 nu))^(1/5)
// (1.411 from the Barenblatt profile of h_t = g / (3 nu) (h^3 h_x)_x).
// A column spreading both ways is two such currents back to back, each of
// half its area.
double huppert_front(double g, double area, double nu, double t);

// The half width of a current spreading both ways from its middle: half of
// (largest - smallest x) among the particles with another within 2 spacings
// (spray left out), plus half a spacing for the edge of the outer particles'
// lattice cells, so that the initial block gives its own half width.
double spreading_half_width(const ParticleFrame& frame, double spacing);

} // namespace sph
