#include "engine/io/motion_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/io/geometry_bounds.h"
#include "engine/io/motion_builder.h"

namespace pfem {

namespace {

bool is_finite(double v) { return std::isfinite(v); }

double distance_to_polyline(const pfem::v1::Wall& w, double x, double y) {
  double best = INFINITY;
  const int n = w.points_size(), count = w.closed() ? n : n - 1;
  for (int k = 0; k < count; ++k) {
    const auto& a = w.points(k);
    const auto& b = w.points((k + 1) % n);
    best = std::min(best, distance_to_segment(x, y, a.x(), a.y(), b.x(), b.y()));
  }
  return best;
}

class MotionChecker {
 public:
  MotionChecker(const pfem::v1::Model& model, int wall)
      : model_(model), wall_(model.walls(wall)), path_("walls[" + std::to_string(wall) + "].motion"),
        wall_path_("walls[" + std::to_string(wall) + "]") {}

  std::vector<FieldError> run() {
    const auto& m = wall_.motion();
    const bool flap = m.kind() == "flap";
    // A slip wall's node has one free velocity component, x or y: its pieces stay horizontal or
    // vertical. A piston translates and keeps them so; a flap turns them.
    if (flap && wall_.slip())
      errors_.push_back({wall_path_ + ".slip", "a flap must be no-slip (it turns its wall, and a slip wall's pieces "
                                               "must stay horizontal or vertical)"});
    if (!flap && m.kind() != "piston") error("kind", "must be \"piston\" or \"flap\" (got \"" + m.kind() + "\")");
    if (!flap && m.has_direction()) {
      if (!is_finite(m.direction().x()) || !is_finite(m.direction().y())) error("direction", "must be finite");
      else if (m.direction().x() == 0.0 && m.direction().y() == 0.0) error("direction", "must not be zero");
    }
    if (flap) check_flap();
    if (m.has_sinusoid()) check_sinusoid();
    else if (m.has_solitary()) check_solitary(flap);
    else if (m.has_table()) check_table();
    else error("", "needs a signal: sinusoid, solitary or table");
    if (errors_.empty()) check_inside_domain();
    if (errors_.empty()) check_stays_on_floor();
    return errors_;
  }

 private:
  void error(const std::string& field, const std::string& message) {
    errors_.push_back({field.empty() ? path_ : path_ + "." + field, message});
  }
  void positive(const std::string& field, double v) {
    if (!is_finite(v) || !(v > 0.0)) error(field, "must be a finite number > 0");
  }

  void check_flap() {
    const auto& m = wall_.motion();
    positive("arm", m.arm());
    if (!is_finite(m.hinge().x()) || !is_finite(m.hinge().y())) return error("hinge", "must be finite");
    const double h = model_.mesh().h();
    if (wall_.points_size() >= 2 && distance_to_polyline(wall_, m.hinge().x(), m.hinge().y()) > 1e-6 * (h > 0 ? h : 1.0))
      error("hinge", "must lie on the wall's line (it is the point the flap turns about)");
  }
  void check_sinusoid() {
    const auto& g = wall_.motion().sinusoid();
    positive("sinusoid.stroke", g.stroke());
    positive("sinusoid.period", g.period());
    if (!is_finite(g.ramp()) || g.ramp() < 0.0) error("sinusoid.ramp", "must be a finite number >= 0");
  }
  void check_solitary(bool flap) {
    const auto& g = wall_.motion().solitary();
    if (flap) error("solitary", "Goring's trajectory is a piston's: use kind \"piston\"");
    positive("solitary.height", g.height());
    positive("solitary.depth", g.depth());
    if (is_finite(g.height()) && is_finite(g.depth()) && g.height() > 0.6 * g.depth())
      error("solitary.height", "must be at most 0.6 depth (a solitary wave breaks above about 0.78 d)");
  }
  void check_table() {
    const auto& g = wall_.motion().table();
    if (g.t_size() < 2) error("table.t", "needs at least 2 times");
    if (g.s_size() != g.t_size())
      error("table.s", "needs one displacement per time (" + std::to_string(g.t_size()) + "), got " +
                           std::to_string(g.s_size()));
    for (int k = 0; k < g.t_size(); ++k) {
      const std::string at = "table.t[" + std::to_string(k) + "]";
      if (!is_finite(g.t(k))) error(at, "must be finite");
      else if (k > 0 && !(g.t(k) > g.t(k - 1))) error(at, "times must increase strictly (this one follows " +
                                                              std::to_string(g.t(k - 1)) + ")");
    }
    for (int k = 0; k < g.s_size(); ++k)
      if (!is_finite(g.s(k))) error("table.s[" + std::to_string(k) + "]", "must be finite");
    if (!g.interpolation().empty() && g.interpolation() != "linear" && g.interpolation() != "cubic")
      error("table.interpolation", "must be \"linear\" or \"cubic\" (got \"" + g.interpolation() + "\")");
    if (g.has_scale()) positive("table.scale", g.scale());
  }
  // The wall's points placed at the signal's samples up to t_end stay in the domain.
  void check_inside_domain() {
    const double t_end = model_.analysis().t_end();
    const Bounds domain = domain_bounds(model_);
    if (!is_finite(t_end) || t_end <= 0.0 || !domain.valid()) return;
    const motion::WallMotion wm = wall_motion(wall_, gravity_magnitude(model_));
    constexpr int kSamples = 4000;
    for (int j = 0; j <= kSamples; ++j) {
      const motion::Sensitive s = wm.signal.displacement(t_end * j / kSamples, {});
      for (const auto& p : wall_.points()) {
        const motion::Placement q = motion::place(wm, s, p.x(), p.y());
        if (q.x < domain.xmin || q.x > domain.xmax || q.y < domain.ymin || q.y > domain.ymax) {
          char text[160];
          std::snprintf(text, sizeof text, "carries the wall's point (%g, %g) out of the domain (to (%g, %g) at t = %g s)",
                        p.x(), p.y(), q.x, q.y, t_end * j / kSamples);
          return error("", text);
        }
      }
    }
  }

  // A point of the wall lying on another wall at rest (a piston's foot on the floor) stays on it:
  // off its end, the water would run out under the paddle.
  void check_stays_on_floor() {
    const double t_end = model_.analysis().t_end(), h = model_.mesh().h();
    if (!is_finite(t_end) || t_end <= 0.0 || !is_finite(h) || h <= 0.0) return;
    const motion::WallMotion wm = wall_motion(wall_, gravity_magnitude(model_));
    const double on = 1e-6 * h;
    constexpr int kSamples = 4000;
    for (const auto& other : model_.walls()) {
      if (&other == &wall_ || other.points_size() < 2) continue;
      for (const auto& p : wall_.points()) {
        if (distance_to_polyline(other, p.x(), p.y()) > on) continue;
        for (int j = 0; j <= kSamples; ++j) {
          const motion::Placement q = motion::place(wm, wm.signal.displacement(t_end * j / kSamples, {}), p.x(), p.y());
          if (distance_to_polyline(other, q.x, q.y) <= on) continue;
          char text[200];
          std::snprintf(text, sizeof text, "carries the wall's point (%g, %g) off the wall '%s' it stands on (to (%g, %g) at t = %g s)",
                        p.x(), p.y(), other.name().c_str(), q.x, q.y, t_end * j / kSamples);
          return error("", text);
        }
      }
    }
  }

  const pfem::v1::Model& model_;
  const pfem::v1::Wall& wall_;
  std::string path_, wall_path_;
  std::vector<FieldError> errors_;
};

}  // namespace

std::vector<FieldError> wall_motion_errors(const pfem::v1::Model& model, int wall) {
  if (!model.walls(wall).has_motion()) return {};
  return MotionChecker(model, wall).run();
}

}  // namespace pfem
