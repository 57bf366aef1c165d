#pragma once
// The CGAL triangulation that remesh() builds and its passes mark (internal to engine/mesh/:
// included only by its .cpp files, so that CGAL stays behind remesher.h).
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cstdint>

namespace pfem::mesh {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Vertex info: the node index.
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>;
// Face info: 1 when the face passed the alpha test and touches a fluid particle ("kept");
// the constrained face base adds the per-edge constraint flags.
using FaceBase = CGAL::Constrained_triangulation_face_base_2<
    Kernel, CGAL::Triangulation_face_base_with_info_2<std::uint8_t, Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Intersection tag: constraints may meet at nodes (walls sharing a corner node, a beam
// clamped at a wall node) and may pass through nodes lying on them, but must not cross in
// their interiors. This tag handles exactly that with exact predicates and never constructs a
// point, so every vertex stays an input node with a valid index. (Exact_predicates_tag would
// accept crossings by inventing a vertex at a rounded intersection point: a vertex with no
// node index, useless to the solver. Exact_intersections_tag needs an exact kernel: slower.)
// A crossing raises Intersection_of_constraints_exception before the triangulation is
// modified for that sub-segment; triangulate_nodes() catches it and leaves the rest of the
// segment out.
using Itag = CGAL::No_constraint_intersection_requiring_constructions_tag;
using Delaunay = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, Itag>;
using Point = Kernel::Point_2;
using VertexHandle = Delaunay::Vertex_handle;
using FaceHandle = Delaunay::Face_handle;

}  // namespace pfem::mesh
