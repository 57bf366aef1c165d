// Unit tests of the PFEM remesher (theory §6, step 1): Delaunay + per-face alpha test,
// removal of triangles without fluid, free-surface detection, input validation.
#include "engine/mesh/remesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using pfem::mesh::FluidMesh;
using pfem::mesh::NodeKind;
using pfem::mesh::RemeshOptions;
using Triangle = std::array<std::int32_t, 3>;
using Segment = std::array<std::int32_t, 2>;

struct Nodes {
  std::vector<double> x, y;
  std::vector<NodeKind> kind;

  std::int32_t add(double px, double py, NodeKind k) {
    x.push_back(px);
    y.push_back(py);
    kind.push_back(k);
    return static_cast<std::int32_t>(x.size() - 1);
  }
  // Without gravity unless given: then "hanging" triangles are dropped too.
  FluidMesh remesh(double h, double alpha, double gy = 0.0) const {
    return pfem::mesh::remesh(x, y, kind, RemeshOptions{h, alpha, 0.0, gy});
  }
  FluidMesh remesh_constrained(double h, double alpha, std::vector<Segment> constraints) const {
    RemeshOptions options{h, alpha};
    options.constraints = std::move(constraints);
    return pfem::mesh::remesh(x, y, kind, options);
  }
};

double signed_area(const Nodes& n, const Triangle& t) {
  const double ux = n.x[t[1]] - n.x[t[0]], uy = n.y[t[1]] - n.y[t[0]];
  const double vx = n.x[t[2]] - n.x[t[0]], vy = n.y[t[2]] - n.y[t[0]];
  return 0.5 * (ux * vy - uy * vx);
}

// Circumcentre by the textbook formula (independent of the remesher's a*b*c/(4A) form).
std::array<double, 3> circumcircle(double ax, double ay, double bx, double by, double cx,
                                   double cy) {
  const double bxr = bx - ax, byr = by - ay, cxr = cx - ax, cyr = cy - ay;
  const double d = 2.0 * (bxr * cyr - byr * cxr);
  const double b2 = bxr * bxr + byr * byr, c2 = cxr * cxr + cyr * cyr;
  const double ux = (cyr * b2 - byr * c2) / d, uy = (bxr * c2 - cxr * b2) / d;
  return {ax + ux, ay + uy, std::sqrt(ux * ux + uy * uy)};
}

double circumradius(const Nodes& n, const Triangle& t) {
  return circumcircle(n.x[t[0]], n.y[t[0]], n.x[t[1]], n.y[t[1]], n.x[t[2]], n.y[t[2]])[2];
}

double total_area(const Nodes& n, const FluidMesh& m) {
  double a = 0.0;
  for (const auto& t : m.triangles) a += signed_area(n, t);
  return a;
}

// Free surface recomputed from the triangle list: both ends of every edge used exactly once
// that has a fluid end (an edge between two wall/structure nodes is a wall, not free) and is
// not one of the constraint segments (walls too).
std::vector<std::uint8_t> free_surface_from_triangles(const Nodes& n, const FluidMesh& m,
                                                      const std::vector<Segment>& walls = {}) {
  std::set<std::pair<std::int32_t, std::int32_t>> constrained;
  for (const auto& [a, b] : walls) constrained.insert({std::min(a, b), std::max(a, b)});
  std::map<std::pair<std::int32_t, std::int32_t>, int> uses;
  for (const auto& t : m.triangles) {
    for (int e = 0; e < 3; ++e) {
      const std::int32_t a = t[e], b = t[(e + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<std::uint8_t> fs(n.x.size(), 0);
  for (const auto& [edge, count] : uses) {
    if (count != 1 || constrained.count(edge)) continue;
    if (n.kind[edge.first] == NodeKind::Fluid || n.kind[edge.second] == NodeKind::Fluid)
      fs[edge.first] = fs[edge.second] = 1;
  }
  return fs;
}

std::vector<std::uint8_t> in_mesh_from_triangles(const Nodes& n, const FluidMesh& m) {
  std::vector<std::uint8_t> in(n.x.size(), 0);
  for (const auto& t : m.triangles) in[t[0]] = in[t[1]] = in[t[2]] = 1;
  return in;
}

// Checks every invariant that holds for any input: sizes, CCW, alpha test, fluid corner,
// in_mesh and free_surface consistent with the triangle list (and the constraint segments,
// which must not contain other nodes).
void expect_consistent(const Nodes& n, const FluidMesh& m, double h, double alpha,
                       const std::vector<Segment>& walls = {}) {
  ASSERT_EQ(m.in_mesh.size(), n.x.size());
  ASSERT_EQ(m.free_surface.size(), n.x.size());
  for (const auto& t : m.triangles) {
    for (const auto v : t) ASSERT_TRUE(v >= 0 && static_cast<std::size_t>(v) < n.x.size());
    EXPECT_GT(signed_area(n, t), 0.0) << "triangle not counter-clockwise";
    EXPECT_LE(circumradius(n, t), alpha * h * (1.0 + 1e-12));
    // A triangle without a particle is a pocket of the water: it shares an edge with another.
    if (n.kind[t[0]] != NodeKind::Fluid && n.kind[t[1]] != NodeKind::Fluid && n.kind[t[2]] != NodeKind::Fluid) {
      int shared = 0;
      for (const auto& u : m.triangles) {
        int common = 0;
        for (const auto a : t) common += std::count(u.begin(), u.end(), a);
        shared += common == 2;
      }
      EXPECT_GT(shared, 0) << "a triangle of wall and structure nodes alone";
    }
  }
  EXPECT_EQ(m.in_mesh, in_mesh_from_triangles(n, m));
  EXPECT_EQ(m.free_surface, free_surface_from_triangles(n, m, walls));
}

Nodes fluid_grid(int nx, int ny, double h, double x0 = 0.0, double y0 = 0.0) {
  Nodes n;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) n.add(x0 + i * h, y0 + j * h, NodeKind::Fluid);
  }
  return n;
}

TEST(Remesher, RegularGridKeepsEveryTriangle) {
  const int nx = 13, ny = 7;
  const double h = 0.05;
  const Nodes n = fluid_grid(nx, ny, h, 1.0, -2.0);
  const FluidMesh m = n.remesh(h, 1.2);

  ASSERT_EQ(m.triangles.size(), static_cast<std::size_t>(2 * (nx - 1) * (ny - 1)));
  const double expected = (nx - 1) * (ny - 1) * h * h;
  EXPECT_NEAR(total_area(n, m), expected, 1e-12 * expected);
  for (const auto& t : m.triangles) {
    EXPECT_NEAR(signed_area(n, t), 0.5 * h * h, 1e-12 * h * h);  // CCW, half a cell
  }
  EXPECT_EQ(std::count(m.in_mesh.begin(), m.in_mesh.end(), 1), nx * ny);
  // A block of fluid alone: its whole outline is free surface, the interior is not.
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool outline = i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
      EXPECT_EQ(m.free_surface[j * nx + i], outline ? 1 : 0) << "node " << i << "," << j;
    }
  }
  expect_consistent(n, m, h, 1.2);
}

TEST(Remesher, SparseOutlierIsLeftOut) {
  const int nx = 8, ny = 6;
  const double h = 0.1;
  Nodes n = fluid_grid(nx, ny, h);
  // 3h to the right of the block's right edge, level with its middle row.
  const std::int32_t outlier = n.add((nx - 1) * h + 3.0 * h, 2.0 * h, NodeKind::Fluid);
  const FluidMesh m = n.remesh(h, 1.2);

  EXPECT_EQ(m.in_mesh[outlier], 0);
  EXPECT_EQ(m.free_surface[outlier], 0);
  for (const auto& t : m.triangles) {
    EXPECT_TRUE(t[0] != outlier && t[1] != outlier && t[2] != outlier);
  }
  EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(2 * (nx - 1) * (ny - 1)));
  const double expected = (nx - 1) * (ny - 1) * h * h;
  EXPECT_NEAR(total_area(n, m), expected, 1e-12 * expected);
  expect_consistent(n, m, h, 1.2);
}

// Open box: wall nodes on y = 0 (x = 0..W), x = 0 and x = W (y = h..H + 2h); fluid
// particles at x = h..W-h, y = h..H. Returns the indices of the top fluid row and of the
// rightmost fluid column.
struct Box {
  Nodes nodes;
  std::set<std::int32_t> top_row, right_column;
  std::set<std::int32_t> waterline_walls;  // side-wall nodes at the water's height
  std::set<std::int32_t> above_waterline;  // side-wall nodes one spacing above it
  std::int32_t bottom_right = -1;          // the bottom wall's last node
};

Box fluid_in_box(int cols, int rows, double h, bool right_wall) {
  Box b;
  const int wall_top = rows + 2;  // the side walls stand two spacings above the water
  for (int i = 0; i <= cols + 1; ++i) b.bottom_right = b.nodes.add(i * h, 0.0, NodeKind::Wall);
  for (int x : {0, right_wall ? cols + 1 : -1}) {
    if (x < 0) continue;
    for (int j = 1; j <= wall_top; ++j) {
      const std::int32_t v = b.nodes.add(x * h, j * h, NodeKind::Wall);
      if (j == rows) b.waterline_walls.insert(v);
      if (j == rows + 1) b.above_waterline.insert(v);
    }
  }
  for (int j = 1; j <= rows; ++j) {
    for (int i = 1; i <= cols; ++i) {
      const std::int32_t v = b.nodes.add(i * h, j * h, NodeKind::Fluid);
      if (j == rows) b.top_row.insert(v);
      if (i == cols) b.right_column.insert(v);
    }
  }
  return b;
}

std::set<std::int32_t> flagged(const std::vector<std::uint8_t>& flags) {
  std::set<std::int32_t> s;
  for (std::size_t i = 0; i < flags.size(); ++i) {
    if (flags[i]) s.insert(static_cast<std::int32_t>(i));
  }
  return s;
}

TEST(Remesher, FreeSurfaceOfWaterInABoxIsTheTopRowAndTheContactLine) {
  const double h = 0.02;
  const int cols = 9, rows = 5;
  const Box box = fluid_in_box(cols, rows, h, /*right_wall=*/true);
  const FluidMesh m = box.nodes.remesh(h, 1.2, /*gy=*/-9.81);

  // With gravity the half-cells (wall, wall, top corner particle) above the water line are
  // dropped: p = 0 on the top row and on the wall nodes at the water line.
  std::set<std::int32_t> expected = box.top_row;
  expected.insert(box.waterline_walls.begin(), box.waterline_walls.end());
  EXPECT_EQ(flagged(m.free_surface), expected);
  for (std::size_t i = 0; i < box.nodes.x.size(); ++i) {
    if (box.nodes.kind[i] == NodeKind::Fluid) {
      EXPECT_EQ(m.in_mesh[i], 1) << "fluid node " << i;
    }
  }
  for (const auto v : box.above_waterline) EXPECT_EQ(m.in_mesh[v], 0) << "wall node " << v;
  // The cells between the walls up to the water line are meshed, except perhaps the
  // wall-only halves of the two bottom corner cells (whichever diagonal CGAL picks there).
  const double water = (cols + 1) * rows * h * h;
  const double area = total_area(box.nodes, m);
  EXPECT_GE(area, water - 1.0 * h * h - 1e-12);
  EXPECT_LE(area, water + 1e-12);
  expect_consistent(box.nodes, m, h, 1.2);
}

TEST(Remesher, WithoutGravityTheWaterWetsOneSpacingUpTheWalls) {
  const double h = 0.02;
  const Box box = fluid_in_box(9, 5, h, /*right_wall=*/true);
  const FluidMesh m = box.nodes.remesh(h, 1.2);
  // The half-cells above the corner particles stay (radius 0.71 h): their upper wall nodes
  // are on free edges, the wall nodes at the water line are inside.
  std::set<std::int32_t> expected = box.top_row;
  expected.insert(box.above_waterline.begin(), box.above_waterline.end());
  EXPECT_EQ(flagged(m.free_surface), expected);
  expect_consistent(box.nodes, m, h, 1.2);
}

TEST(Remesher, FreeSurfaceWithoutRightWallIncludesTheExposedColumn) {
  const double h = 0.02;
  const int cols = 9, rows = 5;
  const Box box = fluid_in_box(cols, rows, h, /*right_wall=*/false);
  const FluidMesh m = box.nodes.remesh(h, 1.2, /*gy=*/-9.81);

  std::set<std::int32_t> expected = box.top_row;
  expected.insert(box.right_column.begin(), box.right_column.end());
  EXPECT_EQ(expected.size(), static_cast<std::size_t>(cols + rows - 1));
  // Contact points: the left wall at the water line, the bottom wall beyond the column.
  expected.insert(box.waterline_walls.begin(), box.waterline_walls.end());
  expected.insert(box.bottom_right);
  EXPECT_EQ(flagged(m.free_surface), expected);
  expect_consistent(box.nodes, m, h, 1.2);
}

TEST(Remesher, TrianglesOfOnlyWallNodesAreRemoved) {
  // A 4 x 3 grid: columns x = 0, h, 2h are walls, column x = 3h is fluid. Only the cells
  // of the last column have a fluid corner (two, whichever diagonal CGAL picks).
  const double h = 1.0;
  Nodes n;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) n.add(i * h, j * h, i == 3 ? NodeKind::Fluid : NodeKind::Wall);
  }
  const FluidMesh m = n.remesh(h, 1.2);
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_NEAR(total_area(n, m), 2.0 * h * h, 1e-12);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) EXPECT_EQ(m.in_mesh[j * 4 + i], i >= 2 ? 1 : 0);
  }
  expect_consistent(n, m, h, 1.2);

  // The same grid with walls only: nothing at all.
  Nodes walls = n;
  std::fill(walls.kind.begin(), walls.kind.end(), NodeKind::Structure);
  const FluidMesh none = walls.remesh(h, 1.2);
  EXPECT_TRUE(none.triangles.empty());
  EXPECT_EQ(std::count(none.in_mesh.begin(), none.in_mesh.end(), 1), 0);
}

// A beam standing on a floor (both constraints) with water beside it: the corner triangle
// of two floor/beam nodes and the beam's first node has no particle, yet it is water (a pocket
// closed by the floor, the beam and a kept triangle). Without the water next to it, it is not.
TEST(Remesher, ACornerPocketBetweenFloorAndBeamIsWater) {
  const double h = 1.0;
  Nodes n;
  const std::int32_t w0 = n.add(0.0, 0.0, NodeKind::Wall), w1 = n.add(1.0, 0.0, NodeKind::Wall);
  const std::int32_t b0 = n.add(2.0, 0.0, NodeKind::Structure), b1 = n.add(2.0, 1.0, NodeKind::Structure);
  const std::int32_t b2 = n.add(2.0, 2.0, NodeKind::Structure);
  const std::vector<Segment> walls{{w0, w1}, {w1, b0}, {b0, b1}, {b1, b2}};
  Nodes dry = n;
  n.add(0.9, 1.2, NodeKind::Fluid);
  n.add(0.0, 1.1, NodeKind::Fluid);
  n.add(1.1, 2.1, NodeKind::Fluid);
  const auto has_corner = [&](const FluidMesh& m) {
    for (const auto& t : m.triangles)
      if (std::is_permutation(t.begin(), t.end(), Triangle{w1, b0, b1}.begin()))
        return true;
    return false;
  };
  const FluidMesh wet = n.remesh_constrained(h, 1.2, walls);
  EXPECT_TRUE(has_corner(wet));
  expect_consistent(n, wet, h, 1.2);
  EXPECT_FALSE(has_corner(dry.remesh_constrained(h, 1.2, walls)));
}

TEST(Remesher, CollinearNodesGiveNoTriangles) {
  Nodes wall_line;
  for (int i = 0; i < 20; ++i) wall_line.add(0.1 * i, 0.05 * i, NodeKind::Wall);
  const FluidMesh m = wall_line.remesh(0.1, 1.2);
  EXPECT_TRUE(m.triangles.empty());
  EXPECT_EQ(std::count(m.in_mesh.begin(), m.in_mesh.end(), 1), 0);

  Nodes fluid_line = wall_line;
  std::fill(fluid_line.kind.begin(), fluid_line.kind.end(), NodeKind::Fluid);
  const FluidMesh f = fluid_line.remesh(0.1, 1.2);
  EXPECT_TRUE(f.triangles.empty());
  EXPECT_EQ(std::count(f.free_surface.begin(), f.free_surface.end(), 1), 0);
}

TEST(Remesher, TinyInputs) {
  Nodes n;
  EXPECT_TRUE(n.remesh(1.0, 1.2).triangles.empty());
  n.add(0.0, 0.0, NodeKind::Fluid);
  n.add(1.0, 0.0, NodeKind::Fluid);
  const FluidMesh two = n.remesh(1.0, 1.2);
  EXPECT_TRUE(two.triangles.empty());
  EXPECT_EQ(two.in_mesh, (std::vector<std::uint8_t>{0, 0}));
  // Given clockwise, returned counter-clockwise.
  n.add(0.0, -1.0, NodeKind::Fluid);
  const FluidMesh three = n.remesh(1.0, 1.2);
  ASSERT_EQ(three.triangles.size(), 1u);
  EXPECT_NEAR(signed_area(n, three.triangles[0]), 0.5, 1e-15);
  EXPECT_EQ(three.free_surface, (std::vector<std::uint8_t>{1, 1, 1}));
  // Circumradius sqrt(2)/2 = 0.7071: kept at alpha*h = 0.71, dropped at 0.70.
  EXPECT_EQ(n.remesh(1.0, 0.71).triangles.size(), 1u);
  EXPECT_EQ(n.remesh(1.0, 0.70).triangles.size(), 0u);
}

// A triangle of three nodes on the previous mesh's boundary (a gap between free surfaces)
// passes only the stricter boundary_alpha test; one interior node in it restores alpha.
TEST(Remesher, GapBetweenPreviousBoundaryNodesNeedsTheBoundaryAlpha) {
  Nodes n;
  n.add(0.0, 0.0, NodeKind::Fluid);
  n.add(1.0, 0.0, NodeKind::Fluid);
  n.add(0.0, -1.0, NodeKind::Fluid);  // circumradius sqrt(2)/2 = 0.7071
  RemeshOptions options{1.0, 0.8};
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 1u);
  options.boundary_alpha = 0.7;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 1u);  // no previous mesh
  const std::vector<std::uint8_t> all{1, 1, 1}, two{1, 0, 1}, short_list{1, 1};
  options.previous_boundary = all;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 0u);
  options.previous_boundary = two;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 1u);
  options.previous_boundary = short_list;  // node 2 is past its end: not flagged
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 1u);
  options.previous_boundary = all;
  options.boundary_alpha = 0.71;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 1u);
  options.boundary_alpha = 2.0;  // above alpha: alpha
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 1u);
  options.boundary_alpha = -0.5;
  EXPECT_THROW(pfem::mesh::remesh(n.x, n.y, n.kind, options), std::invalid_argument);
}

// A triangle whose three nodes were inside the previous mesh (in a previous triangle, none on
// its boundary) passes at 1.25 alpha: circumradius 0.7071 is kept at alpha = 0.6 (0.75), dropped
// at 0.56 (0.70); with a node on the previous boundary or out of the previous mesh, alpha holds.
TEST(Remesher, TrianglesInsideThePreviousWaterPassAtAQuarterMoreAlpha) {
  Nodes n;
  n.add(0.0, 0.0, NodeKind::Fluid);
  n.add(1.0, 0.0, NodeKind::Fluid);
  n.add(0.0, -1.0, NodeKind::Fluid);  // circumradius sqrt(2)/2 = 0.7071
  RemeshOptions options{1.0, 0.6};
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 0u);  // no previous mesh
  const std::vector<std::array<std::int32_t, 3>> previous{{0, 1, 2}}, without_2{{0, 1, 0}};
  const std::vector<std::uint8_t> none{0, 0, 0}, one{0, 1, 0};
  options.previous_triangles = previous;
  options.previous_boundary = none;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 1u);
  options.alpha = 0.56;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 0u);
  options.alpha = 0.6;
  options.previous_boundary = one;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 0u);
  options.previous_boundary = none;
  options.previous_triangles = without_2;
  EXPECT_EQ(pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles.size(), 0u);
}

TEST(Remesher, CoincidentPointsKeepTheLowestIndex) {
  const int nx = 5, ny = 4;
  const double h = 0.1;
  const std::size_t cells = 2 * (nx - 1) * (ny - 1);

  // A later copy of grid node 7 (interior): the copy is left out.
  Nodes later = fluid_grid(nx, ny, h);
  const std::int32_t copy = later.add(later.x[7], later.y[7], NodeKind::Fluid);
  const FluidMesh a = later.remesh(h, 1.2);
  EXPECT_EQ(a.triangles.size(), cells);
  EXPECT_EQ(a.in_mesh[7], 1);
  EXPECT_EQ(a.in_mesh[copy], 0);
  EXPECT_EQ(a.free_surface[copy], 0);
  expect_consistent(later, a, h, 1.2);

  // The copy placed first: now the grid's own node (index 8) is the later duplicate.
  Nodes first;
  first.add(later.x[7], later.y[7], NodeKind::Fluid);
  const Nodes grid = fluid_grid(nx, ny, h);
  for (std::size_t i = 0; i < grid.x.size(); ++i) first.add(grid.x[i], grid.y[i], grid.kind[i]);
  const FluidMesh b = first.remesh(h, 1.2);
  EXPECT_EQ(b.triangles.size(), cells);
  EXPECT_EQ(b.in_mesh[0], 1);
  EXPECT_EQ(b.in_mesh[8], 0);
  EXPECT_EQ(std::count(b.in_mesh.begin(), b.in_mesh.end(), 1), nx * ny);
  expect_consistent(first, b, h, 1.2);

  // Three copies of a corner, -0.0 and 0.0 included: one survives, the lowest index.
  Nodes zeros = fluid_grid(nx, ny, h);  // node 0 is (0, 0)
  const std::int32_t z1 = zeros.add(-0.0, 0.0, NodeKind::Fluid);
  const std::int32_t z2 = zeros.add(0.0, -0.0, NodeKind::Fluid);
  const FluidMesh c = zeros.remesh(h, 1.2);
  EXPECT_EQ(c.in_mesh[0], 1);
  EXPECT_EQ(c.free_surface[0], 1);
  EXPECT_EQ(c.in_mesh[z1], 0);
  EXPECT_EQ(c.in_mesh[z2], 0);
  EXPECT_EQ(c.triangles.size(), cells);
}

TEST(Remesher, InvalidInputThrows) {
  const std::vector<double> x{0.0, 1.0, 0.0}, y{0.0, 0.0, 1.0}, y_short{0.0, 0.0};
  const std::vector<NodeKind> k(3, NodeKind::Fluid), k_short(2, NodeKind::Fluid);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using pfem::mesh::remesh;

  EXPECT_THROW(remesh(x, y_short, k, {1.0, 1.2}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k_short, {1.0, 1.2}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k, {0.0, 1.2}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k, {-1.0, 1.2}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k, {nan, 1.2}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k, {1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k, {1.0, -1.2}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k, {1.0, nan}), std::invalid_argument);
  EXPECT_THROW(remesh(x, y, k, RemeshOptions{}), std::invalid_argument);  // h defaults to 0
  for (const double bad : {nan, inf, -inf}) {
    std::vector<double> xb = x, yb = y;
    xb[1] = bad;
    EXPECT_THROW(remesh(xb, y, k, {1.0, 1.2}), std::invalid_argument);
    yb[2] = bad;
    EXPECT_THROW(remesh(x, yb, k, {1.0, 1.2}), std::invalid_argument);
  }
  try {
    remesh(x, y_short, k, {1.0, 1.2});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("same size"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(remesh(x, y, k, {1.0, 1.2}));
}

// Random cloud: the kept set must equal, triangle for triangle, the brute-force set of
// Delaunay triangles (empty circumcircle) with circumradius <= alpha*h and a fluid corner.
TEST(Remesher, RandomCloudMatchesBruteForce) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> coord(0.0, 1.0), u(0.0, 1.0);
  const int count = 400;
  const double h = 1.0 / std::sqrt(static_cast<double>(count)), alpha = 1.3;
  Nodes n;
  for (int i = 0; i < count; ++i) {
    const double r = u(rng);
    const NodeKind k = r < 0.2 ? NodeKind::Wall : (r < 0.25 ? NodeKind::Structure : NodeKind::Fluid);
    n.add(coord(rng), coord(rng), k);
  }
  const FluidMesh m = n.remesh(h, alpha);
  expect_consistent(n, m, h, alpha);

  // Candidate triples: all pairwise distances <= 2*alpha*h (necessary for R <= alpha*h).
  const double reach2 = 4.0 * alpha * alpha * h * h;
  std::vector<std::vector<int>> near(count);
  for (int i = 0; i < count; ++i) {
    for (int j = i + 1; j < count; ++j) {
      const double dx = n.x[i] - n.x[j], dy = n.y[i] - n.y[j];
      if (dx * dx + dy * dy <= reach2) near[i].push_back(j);
    }
  }
  std::set<Triangle> expected;
  double expected_area = 0.0;
  int borderline = 0;
  for (int i = 0; i < count; ++i) {
    for (const int j : near[i]) {
      for (const int k : near[i]) {
        if (k <= j || std::find(near[j].begin(), near[j].end(), k) == near[j].end()) continue;
        if (n.kind[i] != NodeKind::Fluid && n.kind[j] != NodeKind::Fluid &&
            n.kind[k] != NodeKind::Fluid) {
          continue;
        }
        const auto [cx, cy, r] = circumcircle(n.x[i], n.y[i], n.x[j], n.y[j], n.x[k], n.y[k]);
        if (!(r <= alpha * h)) continue;
        if (std::abs(r - alpha * h) < 1e-9 * h) ++borderline;
        bool empty = true;
        for (int p = 0; p < count && empty; ++p) {
          if (p == i || p == j || p == k) continue;
          const double dx = n.x[p] - cx, dy = n.y[p] - cy;
          empty = dx * dx + dy * dy >= r * r;
        }
        if (!empty) continue;
        expected.insert({i, j, k});
        expected_area += std::abs(signed_area(n, {i, j, k}));
      }
    }
  }
  ASSERT_EQ(borderline, 0) << "seed gives a triangle too close to the alpha threshold";

  std::set<Triangle> actual;
  for (auto t : m.triangles) {
    std::sort(t.begin(), t.end());
    actual.insert(t);
  }
  EXPECT_EQ(actual.size(), m.triangles.size()) << "duplicate triangles";
  EXPECT_EQ(actual, expected);
  EXPECT_NEAR(total_area(n, m), expected_area, 1e-12 * expected_area);
  // Uniform random points leave holes: some, but not all, Delaunay faces fail the test.
  EXPECT_GT(m.triangles.size(), static_cast<std::size_t>(count));
  EXPECT_LT(m.triangles.size(), static_cast<std::size_t>(2 * count));
}

// ---- Constraint segments (walls and beams) ----

int edge_uses(const FluidMesh& m, std::int32_t a, std::int32_t b) {
  int uses = 0;
  for (const auto& t : m.triangles) {
    const bool has_a = t[0] == a || t[1] == a || t[2] == a;
    const bool has_b = t[0] == b || t[1] == b || t[2] == b;
    uses += has_a && has_b;
  }
  return uses;
}

// Triangles with sorted corners, mapped through index_map (identity when empty); only those
// accepted by the filter.
template <class Filter>
std::set<Triangle> triangle_set(const FluidMesh& m, Filter keep,
                                const std::vector<std::int32_t>& index_map = {}) {
  std::set<Triangle> s;
  for (auto t : m.triangles) {
    if (!keep(t)) continue;
    if (!index_map.empty()) {
      for (auto& v : t) v = index_map[v];
    }
    std::sort(t.begin(), t.end());
    s.insert(t);
  }
  return s;
}
std::set<Triangle> triangle_set(const FluidMesh& m) {
  return triangle_set(m, [](const Triangle&) { return true; });
}

// A vertical wall x = 0 (nodes j = 0..rows at (0, j h), consecutive pairs as constraints)
// between two jittered blocks of fluid (cols columns each). Each block's first column stands
// 0.35..0.45 h from the wall, level with the middle of a wall segment: every wall segment has
// particles of both sides strictly inside its diametral circle (distance <= 0.453 h < h/2),
// so no wall segment is a Delaunay edge and plain Delaunay joins the blocks across the wall.
struct WallBetweenBlocks {
  Nodes nodes;
  std::vector<Segment> wall;
  std::int32_t first_right = 0;  // left particles: [rows + 1, first_right); right: the rest
};

WallBetweenBlocks wall_between_blocks(int rows, int cols, double h) {
  WallBetweenBlocks w;
  for (int j = 0; j <= rows; ++j) w.nodes.add(0.0, j * h, NodeKind::Wall);
  for (int j = 0; j < rows; ++j) w.wall.push_back({j, j + 1});
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> jitter(-0.05 * h, 0.05 * h);
  for (const int side : {-1, 1}) {
    if (side == 1) w.first_right = static_cast<std::int32_t>(w.nodes.x.size());
    for (int j = 0; j < rows; ++j) {
      for (int k = 0; k < cols; ++k) {
        const double px = side * (0.4 + k) * h + jitter(rng);
        w.nodes.add(px, (j + 0.5) * h + jitter(rng), NodeKind::Fluid);
      }
    }
  }
  return w;
}

// Corners strictly left (x < 0) and strictly right (x > 0) of the wall line x = 0.
bool spans_x0(const Nodes& n, const Triangle& t) {
  const bool left = n.x[t[0]] < 0.0 || n.x[t[1]] < 0.0 || n.x[t[2]] < 0.0;
  const bool right = n.x[t[0]] > 0.0 || n.x[t[1]] > 0.0 || n.x[t[2]] > 0.0;
  return left && right;
}

// The nodes `keep` of n (in order) and the map from n's indices to the new ones (-1: dropped).
std::pair<Nodes, std::vector<std::int32_t>> subset(const Nodes& n,
                                                   const std::vector<std::int32_t>& keep) {
  Nodes s;
  std::vector<std::int32_t> map(n.x.size(), -1);
  for (const auto i : keep) map[i] = s.add(n.x[i], n.y[i], n.kind[i]);
  return {s, map};
}

TEST(Remesher, WallConstraintKeepsTheTwoSidesApart) {
  const double h = 0.1, alpha = 2.0;  // generous: without the wall, the blocks merge
  const int rows = 10, cols = 3;
  const WallBetweenBlocks w = wall_between_blocks(rows, cols, h);
  const Nodes& n = w.nodes;

  // Without constraints (the old behaviour): triangles span the wall, no wall segment is an
  // edge. This proves the setup.
  const FluidMesh plain = n.remesh(h, alpha);
  const auto spanning = [&](const Triangle& t) { return spans_x0(n, t); };
  EXPECT_GE(triangle_set(plain, spanning).size(), static_cast<std::size_t>(rows));
  for (const auto& [a, b] : w.wall) EXPECT_EQ(edge_uses(plain, a, b), 0) << a << "-" << b;
  expect_consistent(n, plain, h, alpha);

  const FluidMesh m = n.remesh_constrained(h, alpha, w.wall);
  EXPECT_TRUE(triangle_set(m, spanning).empty());
  // Every wall segment is an edge, of one kept triangle on each side.
  for (const auto& [a, b] : w.wall) {
    int left = 0, right = 0;
    for (const auto& t : m.triangles) {
      const std::set<std::int32_t> c(t.begin(), t.end());
      if (!c.count(a) || !c.count(b)) continue;
      for (const auto v : t) {
        if (n.x[v] < 0.0) ++left;
        if (n.x[v] > 0.0) ++right;
      }
    }
    EXPECT_EQ(left, 1) << "segment " << a << "-" << b;
    EXPECT_EQ(right, 1) << "segment " << a << "-" << b;
  }
  // The wall is not free surface, except its two ends where the blocks' outlines meet it.
  for (int j = 0; j <= rows; ++j) EXPECT_EQ(m.free_surface[j], j == 0 || j == rows ? 1 : 0) << j;
  for (std::size_t i = 0; i < n.x.size(); ++i) EXPECT_EQ(m.in_mesh[i], 1) << "node " << i;
  expect_consistent(n, m, h, alpha, w.wall);

  // Each side is meshed independently: exactly as if the other block did not exist.
  for (const int side : {-1, 1}) {
    std::vector<std::int32_t> keep;
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(n.x.size()); ++i) {
      if (n.x[i] == 0.0 || (n.x[i] < 0.0) == (side < 0)) keep.push_back(i);
    }
    const auto [alone, map] = subset(n, keep);  // wall nodes keep their indices
    const FluidMesh one = alone.remesh_constrained(h, alpha, w.wall);
    const auto on_side = [&](const Triangle& t) {
      return side * n.x[t[0]] >= 0.0 && side * n.x[t[1]] >= 0.0 && side * n.x[t[2]] >= 0.0;
    };
    const std::set<Triangle> part = triangle_set(m, on_side, map);
    EXPECT_EQ(part, triangle_set(one)) << "side " << side;
    EXPECT_GT(part.size(), static_cast<std::size_t>(2 * rows));
  }
  EXPECT_EQ(triangle_set(m).size(), m.triangles.size());
}

// A horizontal beam (a line of Structure nodes at y = 0, elements as constraints) with a
// block of fluid below it, and two particles that have crossed it (just above it).
// A particle taken out beside a beam inside the water leaves a void whose triangles fail the
// alpha test. When the water was wet all round it at the previous step (no node of the void on
// that mesh's boundary), air cannot be there: the void is water, and the beam's side stays wet.
// Its ring flagged as a surface (an air pocket), no previous mesh, or a void away from any beam
// leave it out.
TEST(Remesher, AVoidAgainstABeamInWaterWetAllRoundAtThePreviousStepIsWater) {
  const double h = 1.0, alpha = 0.9;  // the grid's triangles: R = 0.707; the void's: R >= 1
  const int nx = 7, ny = 7;
  // A beam up the middle (structure nodes at x = 3, constraints between them), water both sides.
  Nodes n;
  std::vector<Segment> beam;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) n.add(i * h, j * h, i == 3 ? NodeKind::Structure : NodeKind::Fluid);
    if (j > 0) beam.push_back({(j - 1) * nx + 3, j * nx + 3});
  }
  RemeshOptions options{h, alpha};
  options.constraints = beam;
  const FluidMesh previous = pfem::mesh::remesh(n.x, n.y, n.kind, options);
  ASSERT_NEAR(total_area(n, previous), 36.0, 1e-12);
  const auto area = [&](const RemeshOptions& o) { return total_area(n, pfem::mesh::remesh(n.x, n.y, n.kind, o)); };
  n.kind[3 * nx + 4] = NodeKind::Removed;  // beside the beam's node (3, 3)
  EXPECT_LT(area(options), 36.0 - 0.5);    // no previous mesh: a void
  options.previous_triangles = previous.triangles;
  options.previous_boundary = previous.free_surface;
  const FluidMesh filled = pfem::mesh::remesh(n.x, n.y, n.kind, options);
  EXPECT_NEAR(total_area(n, filled), 36.0, 1e-12);
  EXPECT_EQ(filled.free_surface[3 * nx + 3], 0);  // the beam's node beside the void stays wet
  for (const auto& [a, b] : beam) EXPECT_EQ(edge_uses(filled, a, b), 2) << a << "-" << b;
  expect_consistent(n, filled, h, std::sqrt(2.0) + 1e-9, beam);
  // Its ring flagged as a surface (an air pocket the water closed over): it stays air.
  std::vector<std::uint8_t> pocket = previous.free_surface;
  for (const int k : {2 * nx + 4, 2 * nx + 5, 3 * nx + 5, 4 * nx + 4, 4 * nx + 5}) pocket[k] = 1;
  options.previous_boundary = pocket;
  EXPECT_LT(area(options), 36.0 - 0.5);
  // The same particle gone in open water (no beam): its void's triangles (R = 1) pass at 1.25
  // alpha (1.125), their nodes all inside the previous water; flagged as an air pocket, it stays.
  Nodes open = fluid_grid(nx, ny, h);
  RemeshOptions plain{h, alpha};
  const FluidMesh wet = open.remesh(h, alpha);
  plain.previous_triangles = wet.triangles;
  plain.previous_boundary = wet.free_surface;
  open.kind[3 * nx + 4] = NodeKind::Removed;
  EXPECT_NEAR(total_area(open, pfem::mesh::remesh(open.x, open.y, open.kind, plain)), 36.0, 1e-12);
  plain.previous_boundary = pocket;
  EXPECT_LT(total_area(open, pfem::mesh::remesh(open.x, open.y, open.kind, plain)), 36.0 - 0.5);
}

TEST(Remesher, BeamConstraintLeavesItsFarSideEmpty) {
  const double h = 0.1, alpha = 1.3;
  const int elements = 12;
  Nodes n;
  std::vector<Segment> beam;
  for (int j = 0; j <= elements; ++j) n.add(j * h, 0.0, NodeKind::Structure);
  for (int j = 0; j < elements; ++j) beam.push_back({j, j + 1});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.05 * h, 0.05 * h);
  for (int r = 0; r < 4; ++r) {
    for (int j = 0; j < elements; ++j)
      n.add((j + 0.5) * h + jitter(rng), -(0.5 + r) * h + jitter(rng), NodeKind::Fluid);
  }
  const std::int32_t crossed1 = n.add(3.5 * h, 0.05 * h, NodeKind::Fluid);
  const std::int32_t crossed2 = n.add(8.4 * h, 0.03 * h, NodeKind::Fluid);
  const auto above = [&](const Triangle& t) {
    return n.y[t[0]] > 0.0 || n.y[t[1]] > 0.0 || n.y[t[2]] > 0.0;
  };

  // Without constraints the crossed particles are meshed with the water below the beam.
  const FluidMesh plain = n.remesh(h, alpha);
  EXPECT_EQ(plain.in_mesh[crossed1], 1);
  EXPECT_EQ(plain.in_mesh[crossed2], 1);
  EXPECT_GE(triangle_set(plain, above).size(), 2u);

  const FluidMesh m = n.remesh_constrained(h, alpha, beam);
  EXPECT_TRUE(triangle_set(m, above).empty());  // nothing on (or reaching) the far side
  EXPECT_EQ(m.in_mesh[crossed1], 0);
  EXPECT_EQ(m.in_mesh[crossed2], 0);
  EXPECT_EQ(m.free_surface[crossed1], 0);
  for (const auto& [a, b] : beam) EXPECT_EQ(edge_uses(m, a, b), 1) << a << "-" << b;
  // Inner beam nodes are wetted but bound the water: no free surface there.
  for (int j = 1; j < elements; ++j) {
    EXPECT_EQ(m.in_mesh[j], 1) << j;
    EXPECT_EQ(m.free_surface[j], 0) << j;
  }
  expect_consistent(n, m, h, alpha, beam);
  // The water below is meshed as if the crossed particles were not there at all.
  Nodes without = n;
  without.kind[crossed1] = without.kind[crossed2] = NodeKind::Removed;
  const FluidMesh below = without.remesh_constrained(h, alpha, beam);
  EXPECT_EQ(triangle_set(m), triangle_set(below));
  EXPECT_EQ(m.free_surface, below.free_surface);

  // A particle exactly on the beam (between nodes 5 and 6) splits the element. Its two
  // halves bound the water on one side only but are constraints, not free edges: neither
  // the particle nor beam nodes 5 and 6 get p = 0 (without the constraints they would).
  Nodes on = without;
  const std::int32_t p = on.add(5.5 * h, 0.0, NodeKind::Fluid);
  std::vector<Segment> split_beam = beam;
  split_beam[5] = {5, p};
  split_beam.push_back({p, 6});
  for (const bool constrained : {true, false}) {
    const FluidMesh s = constrained ? on.remesh_constrained(h, alpha, beam) : on.remesh(h, alpha);
    EXPECT_EQ(s.in_mesh[p], 1);
    EXPECT_EQ(edge_uses(s, 5, p), 1);
    EXPECT_EQ(edge_uses(s, p, 6), 1);
    for (const std::int32_t v : {5, 6, p}) EXPECT_EQ(s.free_surface[v], constrained ? 0 : 1) << v;
    if (constrained) expect_consistent(on, s, h, alpha, split_beam);
  }
}

TEST(Remesher, ConstraintsWithRemovedOrDuplicateEndsAreSkipped) {
  const double h = 0.1, alpha = 2.0;
  const int rows = 10;
  const WallBetweenBlocks w = wall_between_blocks(rows, 3, h);
  const FluidMesh reference = w.nodes.remesh_constrained(h, alpha, w.wall);

  // Wall node 5 removed: its two segments are skipped, the rest of the wall holds, and water
  // joins across the gap only (between wall nodes 4 and 6).
  Nodes gap = w.nodes;
  gap.kind[5] = NodeKind::Removed;
  FluidMesh m;
  ASSERT_NO_THROW(m = gap.remesh_constrained(h, alpha, w.wall));
  EXPECT_EQ(m.in_mesh[5], 0);
  EXPECT_EQ(m.free_surface[5], 0);
  std::vector<Segment> kept_wall;
  for (const auto& [a, b] : w.wall) {
    if (a == 5 || b == 5) continue;
    kept_wall.push_back({a, b});
    EXPECT_EQ(edge_uses(m, a, b), 2) << a << "-" << b;
  }
  const auto spanning = [&](const Triangle& t) { return spans_x0(gap, t); };
  const std::set<Triangle> leaks = triangle_set(m, spanning);
  EXPECT_FALSE(leaks.empty());  // the gap is open
  for (const auto& t : leaks) {
    for (const auto v : t) {
      EXPECT_GE(gap.y[v], 4.0 * h - 1e-12);
      EXPECT_LE(gap.y[v], 6.0 * h + 1e-12);
    }
  }
  expect_consistent(gap, m, h, alpha, kept_wall);

  // All wall nodes removed: every constraint is skipped, the result is plain Delaunay.
  Nodes no_wall = w.nodes;
  for (int j = 0; j <= rows; ++j) no_wall.kind[j] = NodeKind::Removed;
  EXPECT_EQ(triangle_set(no_wall.remesh_constrained(h, alpha, w.wall)),
            triangle_set(no_wall.remesh(h, alpha)));

  // A merged duplicate of wall node 3 (a later node at the same point) stands for node 3;
  // a segment between the two coincident nodes, and a repeated segment, change nothing.
  Nodes dup = w.nodes;
  const std::int32_t copy = dup.add(0.0, 3.0 * h, NodeKind::Wall);
  std::vector<Segment> via_copy = w.wall;
  via_copy[2] = {2, copy};
  via_copy[3] = {copy, 4};
  via_copy.push_back({3, copy});
  via_copy.push_back({1, 0});
  const FluidMesh d = dup.remesh_constrained(h, alpha, via_copy);
  EXPECT_EQ(d.in_mesh[copy], 0);
  EXPECT_EQ(triangle_set(d), triangle_set(reference));
  EXPECT_EQ(std::vector<std::uint8_t>(d.free_surface.begin(), d.free_surface.end() - 1),
            reference.free_surface);

  // Invalid constraint indices throw.
  const auto n = static_cast<std::int32_t>(w.nodes.x.size());
  for (const Segment bad : {Segment{-1, 0}, Segment{0, n}, Segment{3, 3}}) {
    EXPECT_THROW(w.nodes.remesh_constrained(h, alpha, {{0, 1}, bad}), std::invalid_argument)
        << bad[0] << "-" << bad[1];
  }
}

TEST(Remesher, ConstraintsThroughNodesAndCrossingConstraints) {
  const double h = 0.1, alpha = 2.0;
  const int rows = 10;
  const WallBetweenBlocks w = wall_between_blocks(rows, 3, h);
  const FluidMesh reference = w.nodes.remesh_constrained(h, alpha, w.wall);

  // One segment from the bottom to the top wall node runs through the others: it is split
  // at them, the same as the consecutive pairs.
  const FluidMesh whole = w.nodes.remesh_constrained(h, alpha, {{0, rows}});
  EXPECT_EQ(triangle_set(whole), triangle_set(reference));
  EXPECT_EQ(whole.free_surface, reference.free_surface);

  // A particle lying exactly on a wall segment (between wall nodes 7 and 8) splits it too.
  Nodes on = w.nodes;
  const std::int32_t p = on.add(0.0, 7.5 * h, NodeKind::Fluid);
  const FluidMesh split = on.remesh_constrained(h, alpha, w.wall);
  EXPECT_TRUE(triangle_set(split, [&](const Triangle& t) { return spans_x0(on, t); }).empty());
  EXPECT_EQ(edge_uses(split, 7, p), 2);
  EXPECT_EQ(edge_uses(split, p, 8), 2);
  EXPECT_EQ(edge_uses(split, 7, 8), 0);
  EXPECT_EQ(split.in_mesh[p], 1);
  EXPECT_EQ(split.free_surface[p], 0);
  std::vector<Segment> split_wall = w.wall;
  split_wall[7] = {7, p};
  split_wall.push_back({p, 8});
  expect_consistent(on, split, h, alpha, split_wall);

  // A segment crossing the (already inserted) wall in the interior of both is left out:
  // no node is invented, the result is as without it.
  const std::int32_t left = rows + 1 + 3 * 2;  // row 2, next to the wall
  const std::int32_t right = w.first_right + 3 * 2;
  ASSERT_LT(w.nodes.x[left], 0.0);
  ASSERT_GT(w.nodes.x[right], 0.0);
  ASSERT_NEAR(w.nodes.y[left], 2.5 * h, 0.05 * h);
  ASSERT_NEAR(w.nodes.y[right], 2.5 * h, 0.05 * h);
  std::vector<Segment> crossing = w.wall;
  crossing.push_back({left, right});
  FluidMesh c;
  ASSERT_NO_THROW(c = w.nodes.remesh_constrained(h, alpha, crossing));
  EXPECT_EQ(triangle_set(c), triangle_set(reference));
  EXPECT_EQ(c.free_surface, reference.free_surface);
}

// Prints remesh() times for jittered grids in an open box of walls (left, bottom, right),
// without and with the walls' consecutive node pairs as constraints; never asserts on time.
TEST(Remesher, TimingOfJitteredGrids) {
  for (const int side : {45, 90, 173}) {  // ~2000, ~8100, ~30000 points
    const double h = 0.01;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.2 * h, 0.2 * h);
    Nodes n;
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        const bool wall = i == 0 || j == 0 || i == side - 1;
        n.add(i * h + jitter(rng), j * h + jitter(rng), wall ? NodeKind::Wall : NodeKind::Fluid);
      }
    }
    const auto node = [side](int i, int j) { return static_cast<std::int32_t>(j * side + i); };
    std::vector<std::array<std::int32_t, 2>> walls;
    for (int j = 0; j + 1 < side; ++j) {
      walls.push_back({node(0, j), node(0, j + 1)});
      walls.push_back({node(side - 1, j), node(side - 1, j + 1)});
    }
    for (int i = 0; i + 1 < side; ++i) walls.push_back({node(i, 0), node(i + 1, 0)});

    std::size_t triangles[2] = {0, 0};
    for (const bool constrained : {false, true}) {
      RemeshOptions options{h, 1.3};
      if (constrained) options.constraints = walls;
      std::vector<double> ms;
      for (int rep = 0; rep < 7; ++rep) {
        const auto t0 = std::chrono::steady_clock::now();
        const FluidMesh m = pfem::mesh::remesh(n.x, n.y, n.kind, options);
        const auto t1 = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        triangles[constrained] = m.triangles.size();
      }
      std::sort(ms.begin(), ms.end());
      std::printf("[ timing ] remesh of %zu points, %zu constraints -> %zu triangles: "
                  "median %.2f ms (min %.2f)\n",
                  n.x.size(), options.constraints.size(), triangles[constrained],
                  ms[ms.size() / 2], ms.front());
      EXPECT_GT(triangles[constrained], n.x.size());  // sanity, not timing
    }
    // The walls are far from every particle (>= 0.6 h): the constraints only add the slivers
    // between a zigzag of the jittered wall nodes and the water (pockets, see the remesher).
    EXPECT_GE(triangles[1], triangles[0]);
    EXPECT_LE(triangles[1], triangles[0] + walls.size() / 10);
  }
}

}  // namespace

// Two free surfaces 0.8 h apart (every particle on the previous boundary, no triangle between
// them before): the alpha test alone would close the gap. It closes only where the particles
// move as water does: not while the surfaces approach head-on (the air would become water), but
// when they translate or shear together, when they meet within the step, or where the triangles
// were water already.
TEST(Remesher, AGapBetweenSurfacesClosesOnlyWhereItsParticlesMoveAsWater) {
  constexpr double h = 0.01;
  Nodes n;
  for (int i = 0; i <= 10; ++i) n.add(i * h, 0.0, NodeKind::Fluid);
  for (int i = 0; i < 10; ++i) n.add((i + 0.5) * h, 0.8 * h, NodeKind::Fluid);
  const std::vector<std::uint8_t> boundary(n.x.size(), 1);
  const auto remesh = [&](double upper_vx, double upper_vy, double dt, std::span<const Triangle> previous) {
    std::vector<double> vx(n.x.size(), 0.0), vy(n.x.size(), 0.0);
    for (std::size_t i = 11; i < n.x.size(); ++i) vx[i] = upper_vx, vy[i] = upper_vy;
    RemeshOptions options{h, 1.2};
    options.previous_boundary = boundary;
    options.previous_triangles = previous;
    options.vx = vx, options.vy = vy;
    options.dt = dt;
    return pfem::mesh::remesh(n.x, n.y, n.kind, options).triangles;
  };
  const auto all = n.remesh(h, 1.2).triangles;
  ASSERT_EQ(all.size(), 19u);
  EXPECT_TRUE(remesh(0.0, -1.0, 1e-3, {}).empty());            // closing at 1 m/s: 0.125 of the gap a step
  EXPECT_TRUE(remesh(0.0, 1.0, 1e-3, {}).empty());             // opening
  EXPECT_EQ(remesh(0.0, -10.0, 1e-3, {}).size(), all.size());  // meets within the step
  EXPECT_EQ(remesh(1.0, 0.0, 1e-3, {}).size(), all.size());    // shear
  EXPECT_EQ(remesh(0.0, 0.0, 1e-3, {}).size(), all.size());    // at rest
  EXPECT_EQ(remesh(0.0, -1.0, 1e-3, all).size(), all.size());  // water already
  EXPECT_THROW(remesh(0.0, 0.0, 0.0, {}), std::invalid_argument);  // velocities need a dt
  RemeshOptions short_velocities{h, 1.2};
  const std::vector<double> v(3, 0.0);
  short_velocities.vx = v, short_velocities.vy = v, short_velocities.dt = 1e-3;
  EXPECT_THROW(pfem::mesh::remesh(n.x, n.y, n.kind, short_velocities), std::invalid_argument);
}
