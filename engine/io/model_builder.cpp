#include "engine/io/model_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "engine/io/geometry_bounds.h"
#include "engine/io/model_checks.h"
#include "engine/io/model_io.h"
#include "engine/io/motion_builder.h"
#include "engine/io/parameter_targets.h"
#include "engine/io/structure_builder.h"

namespace pfem {

namespace {

using mesh::NodeKind;

struct Segment {
  double ax, ay, bx, by;
};

// Wall nodes at spacing <= h along each polyline; corners shared by two walls appear once.
// Returns the wall lines (for placing particles) and records the node pairs of every wall
// piece in nodes' segment list.
// The nodes inside a straight piece that no other wall shares slide along it (mesh::SlidingWallNode);
// those of a slip wall also have their tangential velocity free (corners and ends: v = 0).
// wall_pieces[w], wall_nodes[w]: the pieces and the nodes of wall w. A moving wall shares only the
// points its motion leaves in place (a flap's hinge) with other walls: its other nodes are its own,
// also where one coincides with another wall's at rest (the remesher merges them while they do; a
// piston standing on a floor slides along it, and splits the floor's constraint where it stands).
std::vector<Segment> add_walls(const pfem::v1::Model& model, double h, NodeState& nodes,
                               std::vector<std::array<std::int32_t, 2>>& pieces, Problem& pb,
                               std::vector<std::vector<std::array<std::int32_t, 2>>>& wall_pieces,
                               std::vector<std::vector<int>>& wall_nodes) {
  std::vector<Segment> segments;
  std::vector<int> owner(nodes.size(), -1);  // per node: the wall that has it (-1: none)
  std::vector<mesh::SlidingWallNode> candidates;
  std::vector<int> candidate_motion;  // the index among the moving walls of its wall, or -1
  std::vector<int> motion_of(model.walls_size(), -1);
  for (int wi = 0, m = 0; wi < model.walls_size(); ++wi)
    if (model.walls(wi).has_motion()) motion_of[wi] = m++;
  std::vector<std::array<std::int32_t, 2>> candidate_neighbours;
  std::vector<std::uint8_t> candidate_slip;
  std::vector<int> uses;
  const double merge = 1e-6 * h;
  const auto moving = [&](int wall) { return wall >= 0 && model.walls(wall).has_motion(); };
  const auto fixed_point = [&](int wall, double x, double y) {  // a point the wall's motion leaves in place
    if (!moving(wall)) return false;
    const auto& m = model.walls(wall).motion();
    return m.kind() == "flap" && std::hypot(m.hinge().x() - x, m.hinge().y() - y) < merge;
  };
  // The wall nodes by square cell of side h: one within merge (<< h) of a point is in the point's
  // cell or a neighbour's, so finding it costs no scan of every node (that made building a model
  // grow with the square of its wall nodes).
  std::map<std::pair<double, double>, std::vector<std::int32_t>> cells;
  const auto cell = [h](double x, double y) { return std::pair{std::floor(x / h), std::floor(y / h)}; };
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.kind[i] == NodeKind::Wall) cells[cell(nodes.x[i], nodes.y[i])].push_back(static_cast<std::int32_t>(i));
  // The node at (x, y) of wall wi: an existing one there when both walls are fixed, or it is the
  // same wall's, or a moving wall's hinge.
  auto add_unique = [&](int wi, double x, double y) -> std::int32_t {
    // The first node (the lowest index) that (x, y) joins, as a scan in node order would find it.
    std::int32_t found = -1;
    const auto [cx, cy] = cell(x, y);
    for (double dx : {-1.0, 0.0, 1.0})
      for (double dy : {-1.0, 0.0, 1.0}) {
        const auto it = cells.find({cx + dx, cy + dy});
        if (it == cells.end()) continue;
        for (const std::int32_t i : it->second) {
          if ((found >= 0 && i > found) || std::hypot(nodes.x[i] - x, nodes.y[i] - y) >= merge) continue;
          const int other = owner[i];
          if (other == wi || (!moving(wi) && !moving(other)) ||
              (moving(wi) ? fixed_point(wi, x, y) : fixed_point(other, x, y)))
            found = i;
        }
      }
    if (found >= 0) return found;
    // A wall node where a structure node stands (a beam clamped on the floor) takes its exact
    // place and holds v = 0 (a corner): the remesher merges the two, and a node a rounding away
    // would make a needle beside the beam's foot, a slip one moving along the floor under it.
    bool under_structure = false;
    for (const auto& sn : model.structure().nodes())
      if (std::hypot(sn.x() - x, sn.y() - y) < merge) x = sn.x(), y = sn.y(), under_structure = true;
    const std::int32_t node = nodes.add(x, y, NodeKind::Wall);
    cells[cell(x, y)].push_back(node);
    owner.resize(nodes.size(), wi);
    uses.resize(nodes.size(), 0);
    uses[node] += under_structure;
    return node;
  };
  for (int wi = 0; wi < model.walls_size(); ++wi) {
    const auto& w = model.walls(wi);
    const std::size_t first_piece = pieces.size();
    wall_nodes.emplace_back();
    const int n = w.points_size();
    const int count = w.closed() ? n : n - 1;
    for (int k = 0; k < count; ++k) {
      const auto& a = w.points(k);
      const auto& b = w.points((k + 1) % n);
      segments.push_back({a.x(), a.y(), b.x(), b.y()});
      const double len = std::hypot(b.x() - a.x(), b.y() - a.y());
      const int count_pieces = std::max(1, static_cast<int>(std::ceil(len / h - 1e-9)));
      std::int32_t previous = -1;
      const double tx = (b.x() - a.x()) / len, ty = (b.y() - a.y()) / len;
      for (int j = 0; j <= count_pieces; ++j) {
        const double t = static_cast<double>(j) / count_pieces;
        const std::int32_t node = add_unique(wi, a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y()));
        if (wall_nodes.back().empty() || wall_nodes.back().back() != node) wall_nodes.back().push_back(node);
        if (previous >= 0) pieces.push_back({previous, node});
        uses.resize(nodes.size(), 0);
        ++uses[node];
        if (j > 1) candidate_neighbours.back()[1] = node;  // the previous node was inside the piece
        if (j > 0 && j < count_pieces) {
          // Freely less than half the spacing either way: it never reaches a neighbour's reach. It
          // covers half the spacing and a hair (a foot at the very middle, as a grid row can be,
          // is not lost to round-off between two nodes).
          const double spacing = len / count_pieces;
          candidates.push_back({node, nodes.x[node], nodes.y[node], tx, ty, 0.49 * spacing, (0.5 + 1e-9) * spacing});
          candidate_neighbours.push_back({previous, -1});
          candidate_slip.push_back(!w.slip() ? 0 : std::abs(tx) > 0.5 ? kSlipX : kSlipY);
          candidate_motion.push_back(motion_of[wi]);
        }
        previous = node;
      }
    }
    wall_pieces.emplace_back(pieces.begin() + first_piece, pieces.end());
    if (w.closed() && wall_nodes.back().size() > 1 && wall_nodes.back().back() == wall_nodes.back().front())
      wall_nodes.back().pop_back();
  }
  pb.wall_neighbours.assign(nodes.size(), {});
  pb.wall_slip.assign(nodes.size(), 0);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (uses[candidates[c].node] != 1) continue;
    pb.wall_slip[candidates[c].node] = candidate_slip[c];
    const int k = static_cast<int>(pb.sliding_walls.size());
    pb.sliding_walls.push_back(candidates[c]);
    pb.sliding_walls.back().neighbours = candidate_neighbours[c];
    pb.sliding_motion.push_back(candidate_motion[c]);
    pb.wall_neighbours[candidates[c].node].push_back(k);
    for (const std::int32_t n : candidate_neighbours[c])
      if (n >= 0) pb.wall_neighbours[n].push_back(k);
  }
  return segments;
}

// The pieces of a boundary as the triangulation may hold them: each piece, and where wall or
// structure nodes lie on it at t = 0 (a beam clamped on the floor, a wall node at a beam's end),
// its parts between them (the remesher splits a constraint at a node on it and merges coincident
// nodes into the lowest index). tol: the distance that counts as on it [m].
std::vector<std::array<std::int32_t, 2>> pieces_as_meshed(const std::vector<std::array<std::int32_t, 2>>& pieces,
                                                          const NodeState& nodes, double tol) {
  std::vector<std::array<std::int32_t, 2>> out;
  for (const auto& [a, b] : pieces) {
    out.push_back({a, b});
    const double dx = nodes.x[b] - nodes.x[a], dy = nodes.y[b] - nodes.y[a], len2 = dx * dx + dy * dy;
    std::vector<std::pair<double, std::int32_t>> on;  // (position along the piece, node)
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (nodes.kind[i] == NodeKind::Fluid || nodes.kind[i] == NodeKind::Removed) continue;
      const double s = ((nodes.x[i] - nodes.x[a]) * dx + (nodes.y[i] - nodes.y[a]) * dy) / len2;
      const double off = std::abs((nodes.x[i] - nodes.x[a]) * dy - (nodes.y[i] - nodes.y[a]) * dx) / std::sqrt(len2);
      if (off < tol && s > -tol && s < 1.0 + tol) on.emplace_back(s, static_cast<std::int32_t>(i));
    }
    std::sort(on.begin(), on.end());
    if (on.size() == 2) continue;  // just the ends
    for (std::size_t j = 1; j < on.size(); ++j) {
      // Coincident nodes are one vertex: the edge runs from the lowest index of each group.
      if (on[j].first - on[j - 1].first < tol) continue;
      std::int32_t from = on[j - 1].second;
      for (std::size_t i = j - 1; i-- > 0 && on[j - 1].first - on[i].first < tol;) from = std::min(from, on[i].second);
      std::int32_t to = on[j].second;
      for (std::size_t i = j + 1; i < on.size() && on[i].first - on[j].first < tol; ++i) to = std::min(to, on[i].second);
      out.push_back({from, to});
    }
  }
  return out;
}

bool inside_polygon(const pfem::v1::Polygon& poly, double x, double y, double tol) {
  // Points on an edge (within tol) count as inside, so that grid points on the boundary are kept.
  const int n = poly.points_size();
  bool inside = false;
  for (int i = 0, j = n - 1; i < n; j = i++) {
    const auto& a = poly.points(i);
    const auto& b = poly.points(j);
    if (distance_to_segment(x, y, a.x(), a.y(), b.x(), b.y()) <= tol) return true;
    if ((a.y() > y) != (b.y() > y) && x < (b.x() - a.x()) * (y - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

// Particles on a grid of spacing h anchored at the region's lower-left corner; those closer
// than h/2 to a wall or to a particle of an earlier region are left out (walls already
// bound the fluid; overlapping regions do not double the water). A polygon's edges get a line
// of particles at a spacing of at most h first, and grid points closer than h/2 to them are
// left out: a sloped or curved surface is a smooth line of particles, not a staircase of h.
void add_region(const pfem::v1::FluidRegion& region, double h, const std::vector<Segment>& walls,
                NodeState& nodes, std::size_t first_particle) {
  const auto clear_of = [&](double x, double y, std::size_t first, std::size_t last) {
    for (const auto& s : walls)
      if (distance_to_segment(x, y, s.ax, s.ay, s.bx, s.by) < 0.5 * h) return false;
    for (std::size_t k = first; k < last; ++k)
      if (std::hypot(nodes.x[k] - x, nodes.y[k] - y) < 0.5 * h) return false;
    return true;
  };
  const auto add = [&](double x, double y) {
    nodes.add(x, y, NodeKind::Fluid, region.velocity().x(), region.velocity().y());
  };
  if (region.has_polygon()) {
    const auto& poly = region.polygon();
    const int n = poly.points_size();
    for (int i = 0; i < n; ++i) {
      const auto& a = poly.points(i);
      const auto& b = poly.points((i + 1) % n);
      const int pieces = std::max(1, static_cast<int>(std::ceil(std::hypot(b.x() - a.x(), b.y() - a.y()) / h - 1e-9)));
      for (int j = 0; j < pieces; ++j) {  // the end point is the next edge's first
        const double t = static_cast<double>(j) / pieces;
        const double x = a.x() + t * (b.x() - a.x()), y = a.y() + t * (b.y() - a.y());
        if (clear_of(x, y, first_particle, nodes.size())) add(x, y);
      }
    }
  }
  const std::size_t outline_end = nodes.size();
  Bounds b;
  if (region.has_rectangle()) {
    b = {region.rectangle().min().x(), region.rectangle().min().y(), region.rectangle().max().x(),
         region.rectangle().max().y()};
  } else {
    b = polygon_bounds(region.polygon());
  }
  const double tol = 1e-9 * h;
  const int nx = static_cast<int>(std::floor((b.xmax - b.xmin) / h + 1e-9));
  const int ny = static_cast<int>(std::floor((b.ymax - b.ymin) / h + 1e-9));
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = b.xmin + i * h, y = b.ymin + j * h;
      if (region.has_polygon() && !inside_polygon(region.polygon(), x, y, tol)) continue;
      if (clear_of(x, y, first_particle, outline_end)) add(x, y);  // earlier regions and this outline
    }
  }
}

int nearest_node(const NodeState& nodes, double x, double y) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double d = std::hypot(nodes.x[i] - x, nodes.y[i] - y);
    if (d < best_d) best_d = d, best = static_cast<int>(i);
  }
  return best;
}

// Each differentiated parameter's seeded targets: weight 1 on its own targets, or w_k on those of
// every parameter k a directional one weighs.
std::vector<std::vector<SeedTarget>> seeded_targets(const pfem::v1::Model& model,
                                                    const std::vector<std::string>& names) {
  const auto find = [&](const std::string& name) -> const pfem::v1::Parameter& {  // checked: it exists
    return *std::find_if(model.parameters().begin(), model.parameters().end(),
                         [&](const auto& q) { return q.name() == name; });
  };
  std::vector<std::vector<SeedTarget>> targets;
  for (const auto& name : names) {
    const pfem::v1::Parameter& p = find(name);
    std::vector<SeedTarget> seeded;
    for (const auto& t : p.targets()) seeded.push_back({t, 1.0});
    for (const auto& w : p.direction())  // validated: each names a parameter with targets
      for (const auto& t : find(w.parameter()).targets()) seeded.push_back({t, w.weight()});
    targets.push_back(std::move(seeded));
  }
  return targets;
}

}  // namespace

std::vector<FieldError> model_errors(const pfem::v1::Model& model) {
  auto errors = validate_model(model);
  if (!errors.empty()) return errors;
  try {
    build_validated_problem(model);
  } catch (const ModelError& e) {
    return e.errors();
  }
  return {};
}

Problem build_problem(const pfem::v1::Model& model, const std::vector<std::string>& sensitivity_params) {
  if (auto errors = validate_model(model); !errors.empty()) throw ModelError(std::move(errors));
  return build_validated_problem(model, sensitivity_params);
}

Problem build_validated_problem(const pfem::v1::Model& model, const std::vector<std::string>& sensitivity_params) {
  // The model with every parameter's value on its targets: the fluid, the thickness, the walls'
  // motions and the structure are built from it.
  pfem::v1::Model with_values = model;
  apply_parameter_overrides(with_values);
  Problem pb;
  pb.fluid = {with_values.fluid().rho(), with_values.fluid().mu(), with_values.fluid().kappa()};
  pb.thickness = model_target_value(with_values, "thickness");
  if (model.has_gravity()) pb.gx = model.gravity().x(), pb.gy = model.gravity().y();
  pb.h = model.mesh().h();
  pb.alpha = model.mesh().has_alpha() ? model.mesh().alpha() : 1.2;
  if (model.mesh().has_removal_distance()) pb.removal_distance = model.mesh().removal_distance();
  if (model.mesh().has_insertion_length()) pb.insertion_length = model.mesh().insertion_length();
  if (model.mesh().has_interior_insertion_length())
    pb.interior_insertion_length = model.mesh().interior_insertion_length();
  if (pb.interior_insertion_length == 0.0) pb.interior_insertion_length = pb.insertion_length;
  if (model.mesh().has_boundary_alpha()) pb.boundary_alpha = model.mesh().boundary_alpha();
  if (model.mesh().has_volume_relaxation_steps()) pb.volume_relaxation_steps = model.mesh().volume_relaxation_steps();
  const auto& a = model.analysis();
  pb.dt = a.dt();
  pb.t_end = a.t_end();
  if (a.has_newton_tolerance()) pb.newton_tolerance = a.newton_tolerance();
  if (a.has_newton_max_iterations()) pb.newton_max_iterations = a.newton_max_iterations();
  if (a.has_record_every()) pb.record_every = a.record_every();
  pb.unified_fractional_step = a.has_solver() && a.solver() == "unified-fractional-step";
  pb.incompressible = is_incompressible(model);
  if (a.has_vtk_every()) pb.vtk_every = a.vtk_every();

  const Bounds domain = domain_bounds(model);
  pb.domain = {domain.xmin, domain.ymin, domain.xmax, domain.ymax};
  pb.fail_on_exit = model.has_domain() && model.domain().on_exit() == "fail";

  const std::vector<ParameterSeed> seeds = parameter_seeds(with_values, seeded_targets(model, sensitivity_params));
  pb.sensitivity_params = sensitivity_params;
  for (const auto& seed : seeds) pb.fluid_seeds.push_back(seed.fluid);
  std::vector<std::vector<std::array<std::int32_t, 2>>> wall_pieces;
  std::vector<std::vector<int>> wall_nodes;
  auto segments = add_walls(model, pb.h, pb.nodes, pb.wall_segments, pb, wall_pieces, wall_nodes);
  pb.moving_walls = build_wall_motions(with_values, wall_nodes, seeds);
  std::map<std::string, std::vector<std::array<std::int32_t, 2>>> boundary_pieces;  // walls, then beams
  std::map<std::string, std::array<double, 2>> boundary_origin;
  for (int w = 0; w < model.walls_size(); ++w) {
    const auto& first = model.walls(w).points(0);
    boundary_pieces.emplace(model.walls(w).name(), wall_pieces[w]);
    boundary_origin.emplace(model.walls(w).name(), std::array<double, 2>{first.x(), first.y()});
  }
  std::map<std::string, int> structure_node_by_name, element_by_name;
  if (model.has_structure()) {
    StructureBuild sb = build_structure(with_values, seeds, /*validated=*/true);
    for (int k = 0; k < sb.model.num_nodes(); ++k) {
      const auto& node = sb.model.node(k);
      pb.structure_nodes.push_back(pb.nodes.add(node.x(0), node.x(1), NodeKind::Structure));
    }
    for (const auto& [name, k] : sb.node_index) structure_node_by_name[name] = pb.structure_nodes[k];
    for (std::size_t b = 0; b < sb.beam_nodes.size(); ++b) {
      const auto& beam = sb.beam_nodes[b];
      const std::string& name = model.structure().beams(static_cast<int>(b)).name();
      const auto& base = sb.model.node(beam.front());
      boundary_origin.emplace(name, std::array<double, 2>{base.x(0), base.x(1)});
      for (std::size_t j = 1; j < beam.size(); ++j) {
        const int from = beam[j - 1], to = beam[j];
        pb.beam_segments.push_back({pb.structure_nodes[from], pb.structure_nodes[to]});
        boundary_pieces[name].push_back(pb.beam_segments.back());
        const auto& na = sb.model.node(from);
        const auto& nb = sb.model.node(to);
        segments.push_back({na.x(0), na.x(1), nb.x(0), nb.x(1)});  // particles keep clear of beams too
      }
    }
    element_by_name = sb.element_index;
    pb.structure_self_weight = !model.structure().has_self_weight() || model.structure().self_weight();
    pb.structure = std::move(sb.model);
  }
  const std::size_t first_particle = pb.nodes.size();
  std::vector<FieldError> errors;
  for (int i = 0; i < model.fluid_regions_size(); ++i) {
    const std::size_t before = pb.nodes.size();
    add_region(model.fluid_regions(i), pb.h, segments, pb.nodes, first_particle);
    if (pb.nodes.size() == before)
      errors.push_back({"fluid_regions[" + std::to_string(i) + "]", "holds no particle clear of the walls at spacing mesh.h"});
  }
  const auto any_outside = [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i)
      if (!pb.domain.contains(pb.nodes.x[i], pb.nodes.y[i])) return true;
    return false;
  };
  if (any_outside(0, first_particle)) errors.push_back({"domain", "does not contain every wall and structure node"});
  if (any_outside(first_particle, pb.nodes.size())) errors.push_back({"domain", "does not contain every fluid particle"});
  if (!errors.empty()) throw ModelError(std::move(errors));

  for (const auto& r : model.recorders()) {
    RecorderSpec spec;
    spec.name = r.name(), spec.quantity = r.quantity();
    if (r.has_point() && is_point_quantity(r.quantity())) spec.x = r.point().x(), spec.y = r.point().y();
    else if (r.has_point()) spec.node = nearest_node(pb.nodes, r.point().x(), r.point().y());
    if (r.has_node()) spec.node = structure_node_by_name.at(r.node());  // validated above
    if (r.has_element()) {
      spec.element = element_by_name.at(r.element());
      spec.component = r.component(), spec.section_point = r.section_point(), spec.fiber = r.fiber();
    }
    if (r.has_boundary()) {  // validated: names a wall or a beam
      spec.pieces = pieces_as_meshed(boundary_pieces.at(r.boundary()), pb.nodes, 1e-6 * pb.h);
      const auto origin = boundary_origin.at(r.boundary());
      spec.x = r.has_about() ? r.about().x() : origin[0], spec.y = r.has_about() ? r.about().y() : origin[1];
    }
    pb.recorders.push_back(spec);
  }
  const std::vector<double> values = parameter_values(with_values);
  for (int i = 0; i < model.parameters_size(); ++i) {
    const auto& p = model.parameters(i);
    ParameterSpec spec{p.name(), {p.targets().begin(), p.targets().end()}, values[i], {}};
    for (const auto& w : p.direction()) spec.direction.emplace_back(w.parameter(), w.weight());
    pb.parameters.push_back(spec);
  }
  pb.nodes.set_num_params(static_cast<int>(sensitivity_params.size()));
  return pb;
}

}  // namespace pfem
