#pragma once
// Where the free surface meets a wall (the contact line). A wall is a polyline of fixed nodes at
// a spacing of about h; the water's surface reaches the wall at its own height, which is in
// general between two wall nodes. The free edge from the last surface particle then ends at a
// wall node up to h above or below the water: its p = 0 sits at the wrong height, the pressure
// near the wall cannot be hydrostatic, and still water next to the wall starts to move (it sinks
// there, and at water's viscosity the surface breaks up). A no-slip or slip wall is the same at
// every point of its line, so which of its points are nodes is free: before each remeshing the
// wall node nearest the wall's point level with a contact particle (square to gravity) slides
// along its straight wall piece to that point, and every other node returns to its place. The
// surface then meets the wall at the particle's height, level as still water is. (To the foot,
// square to the wall, the free edge on a wall at 60 degrees sloped at 30 degrees, and still water
// between two such walls moved at 0.18 m/s.) Where no node next to the contact covers the level
// point (a level wall; a gentle slope with the particle a few tenths of the spacing off it, the
// point then spacings away up the wall) the node goes to the foot, as a film's edge does.
// A node slides freely by less than half the spacing, so two never meet; to a point nearer the
// middle between it and its neighbour than that (in the sliver between their reaches) it slides
// when the neighbour has not moved, which then stays at its place, and otherwise stops at its
// reach, 1 % of the spacing short. Without the sliver's rule the contact node stayed at its
// place there, ending the surface half a spacing above or below the water: still water at
// μ = 1e-3 whose surface lay at such a middle moved at 0.36 m/s, its area off by 0.6 %, in
// 2 s, and sloshing in a 0.7 m tank at h = 0.0163 m (its surface 0.3 mm off a middle) ran 6.8 %
// slow with its waves growing.
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/remesher.h"

namespace pfem::mesh {

// A wall node inside a straight wall piece (not a corner or an end): it follows the feet nearer
// to its place than to its neighbours', freely by less than half the spacing to them.
struct SlidingWallNode {
  std::int32_t node = -1;
  double home_x = 0.0, home_y = 0.0;  // its place on the wall line
  double tx = 0.0, ty = 0.0;          // unit tangent of the wall piece
  double reach = 0.0;                 // largest free slide either way [m]
  double cover = 0.0;                 // a point this near its place is its to follow: half the spacing and a hair [m]
  // The wall nodes next to it on its piece, behind and ahead of it along the tangent.
  std::array<std::int32_t, 2> neighbours{-1, -1};

  // How far along the wall from home the point (x, y) lies, (p - h).u: its foot.
  double offset(double x, double y) const { return (x - home_x) * tx + (y - home_y) * ty; }
  // Its derivative, with (dx, dy) the point's and dh = d(home_x, home_y, tx, ty) the wall's:
  // (dp - dh).u + (p - h).du.
  double offset_derivative(double x, double y, double dx, double dy, const std::array<double, 4>& dh) const {
    return (dx - dh[0]) * tx + (dy - dh[1]) * ty + (x - home_x) * dh[2] + (y - home_y) * dh[3];
  }
  // How far along the wall from home the wall's point level with (x, y) lies, with l the unit
  // level direction (square to gravity): ((p - h) x l) / (u x l); false for a wall along l.
  bool level_offset(double x, double y, const std::array<double, 2>& l, double& o) const {
    const double ul = tx * l[1] - ty * l[0];
    if (std::abs(ul) < kLevelWall) return false;
    o = ((x - home_x) * l[1] - (y - home_y) * l[0]) / ul;
    return true;
  }
  // Its derivative: ((dp - dh) x l - o du x l) / (u x l).
  double level_offset_derivative(double o, double dx, double dy, const std::array<double, 4>& dh,
                                 const std::array<double, 2>& l) const {
    const double ul = tx * l[1] - ty * l[0];
    return ((dx - dh[0]) * l[1] - (dy - dh[1]) * l[0] - o * (dh[2] * l[1] - dh[3] * l[0])) / ul;
  }
  // Below this sine of its slope a wall counts as level (its level point at infinity).
  static constexpr double kLevelWall = 1e-6;
};

// The unit level direction, square to gravity (gx, gy); {0, 0} without gravity.
inline std::array<double, 2> level_direction(double gx, double gy) {
  const double g = std::hypot(gx, gy);
  return g > 0.0 ? std::array{-gy / g, gx / g} : std::array{0.0, 0.0};
}

// Where a sliding node goes: sliding[index] at its home + offset * tangent, following the
// particle's position.
struct WallSlide {
  int index = -1;
  std::int32_t particle = -1;
  double offset = 0.0;
  bool follows = true;  // offset is the particle's; false: held at the node's reach, short of it
  bool level = false;   // to the wall's point level with the particle, not to its foot
};

// The slides for the contact edges of the previous mesh (FluidMesh::contact_edges: a free edge
// between a particle and a wall node; a structure node's, which does not slide, is passed over), at the current particle positions x, y. For each contact
// edge, of the sliding nodes among the wall node itself and its wall neighbours (neighbours[wall]:
// indices into `sliding`) that cover the wall's point level with the particle (level: a unit
// vector square to gravity, {0, 0} for none), or else its foot, the one nearest that point
// slides there (past its reach only while the neighbour on that side stays at its place, else to
// its reach); the contacts nearest a node go first, and a node takes the first that claims it.
// Deterministic, and independent of the order of the contact edges.
std::vector<WallSlide> contact_line_slides(const FluidMesh& previous, std::span<const double> x,
                                           std::span<const double> y, std::span<const SlidingWallNode> sliding,
                                           const std::vector<std::vector<int>>& neighbours,
                                           const std::array<double, 2>& level);

}  // namespace pfem::mesh
