#pragma once
// Where the free surface meets a beam between two of its nodes. A beam's nodes are the
// structure's and stay where it puts them, so the free edge from the last surface particle ends
// at a beam node up to a segment above or below the water: its p = 0 sits at the wrong height,
// the pressure next to the beam cannot be hydrostatic, and still water there starts to move
// (40 mm of water against a stiff plate of 7.1 mm elements, h = 5 mm, mu = 1e-3: 0.11 m/s within
// 1 s). Walls slide a node to the contact (contact_line.h); a beam gets a rider instead: a node
// on the segment at the beam's point level with the contact particle (square to gravity), which
// splits the segment for the remeshing (LineRider) and moves with the beam between the
// segment's ends (StepRider, engine/solve/step_numbering.h). Each segment has at most one.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/remesher.h"

namespace pfem::mesh {

// A rider's place: on segments[segment] at a + s (b - a), level with the particle.
struct RiderPlace {
  int segment = -1;
  std::int32_t particle = -1;
  double s = 0.0;
};

// The fraction s of the segment from a to b at which its point is level with p (l: the unit
// level direction): ((p - a) x l) / ((b - a) x l); false for a segment within 1e-6 of level.
bool level_fraction(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& p,
                    const std::array<double, 2>& l, double& s);
// Its derivative from those of a, b and p: ((dp - da) x l - s (db - da) x l) / ((b - a) x l).
double level_fraction_derivative(const std::array<double, 2>& a, const std::array<double, 2>& b, double s,
                                 const std::array<double, 2>& da, const std::array<double, 2>& db,
                                 const std::array<double, 2>& dp, const std::array<double, 2>& l);

// A rider nearer an end than this fraction of its segment is not placed: the end covers it (as a
// wall's contact node stops 1 % of the spacing short of its neighbour). Still water whose level
// lies 0.5 % of an element above a beam node moves at 7e-5 m/s; at 2 % and beyond, with a rider,
// at rest (7e-6 m/s).
inline constexpr double kRiderMargin = 0.01;
// Nor one whose point is farther from its particle than this many particle spacings.
inline constexpr double kRiderReach = 2.0;

// The riders for the contact edges of the previous mesh (FluidMesh::contact_edges to beam nodes
// or to riders), at the current positions x, y: for each contact, of the segments of its beam
// node (segments_of[node]; for the rider of segment j, node first_rider + j, those of j's ends) the one
// whose point level with the particle lies between its ends (kRiderMargin) and nearest the
// particle (within kRiderReach h); a segment takes the nearest of the contacts that claim it.
// Deterministic, independent of the order of the contact edges.
std::vector<RiderPlace> place_riders(const FluidMesh& previous, std::span<const double> x, std::span<const double> y,
                                     std::span<const std::array<std::int32_t, 2>> segments,
                                     const std::vector<std::vector<int>>& segments_of, std::int32_t first_rider,
                                     const std::array<double, 2>& level, double h);

}  // namespace pfem::mesh
