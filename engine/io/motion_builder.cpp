#include "engine/io/motion_builder.h"

#include <cmath>

namespace pfem {

namespace {
motion::Signal signal_of(const pfem::v1::WallMotion& m, double gravity) {
  motion::Signal g;
  if (m.has_sinusoid()) {
    g.kind = motion::Signal::Kind::kSinusoid;
    g.stroke = m.sinusoid().stroke(), g.period = m.sinusoid().period(), g.ramp = m.sinusoid().ramp();
  } else if (m.has_solitary()) {
    g.kind = motion::Signal::Kind::kSolitary;
    g.height = m.solitary().height(), g.depth = m.solitary().depth(), g.gravity = gravity;
  } else {  // validated: a table
    g.kind = motion::Signal::Kind::kTable;
    g.times.assign(m.table().t().begin(), m.table().t().end());
    g.values.assign(m.table().s().begin(), m.table().s().end());
    g.cubic = m.table().interpolation() == "cubic";
    g.scale = m.table().has_scale() ? m.table().scale() : 1.0;
  }
  g.prepare();
  return g;
}
}  // namespace

motion::WallMotion wall_motion(const pfem::v1::Wall& wall, double gravity) {
  const auto& m = wall.motion();
  motion::WallMotion wm;
  wm.flap = m.kind() == "flap";
  if (m.has_direction()) {  // validated: not zero
    const double norm = std::hypot(m.direction().x(), m.direction().y());
    wm.direction_x = m.direction().x() / norm, wm.direction_y = m.direction().y() / norm;
  }
  wm.hinge_x = m.hinge().x(), wm.hinge_y = m.hinge().y(), wm.arm = m.arm();
  wm.signal = signal_of(m, gravity);
  return wm;
}

double gravity_magnitude(const pfem::v1::Model& model) {
  return model.has_gravity() ? std::hypot(model.gravity().x(), model.gravity().y()) : 9.81;
}

std::vector<motion::WallMotion> build_wall_motions(const pfem::v1::Model& model,
                                                   const std::vector<std::vector<int>>& wall_nodes,
                                                   const std::vector<ParameterSeed>& seeds) {
  std::vector<motion::WallMotion> out;
  for (int w = 0; w < model.walls_size(); ++w) {
    const auto& wall = model.walls(w);
    if (!wall.has_motion()) continue;
    motion::WallMotion wm = wall_motion(wall, gravity_magnitude(model));
    wm.nodes = wall_nodes[w];
    for (const auto& seed : seeds) wm.seeds.push_back(seed.walls[w]);
    out.push_back(std::move(wm));
  }
  return out;
}

}  // namespace pfem
