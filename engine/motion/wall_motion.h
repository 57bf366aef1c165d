#pragma once
// Walls with a prescribed rigid motion (wavemakers): the displacement signal s(t) of a piston
// or a flap (model.proto, WallMotion), where it puts each of the wall's points at time t, and
// the derivatives of both with respect to the signal's parameters, which the DDM takes as the
// prescribed sensitivities of the wall's nodes.
#include <vector>

namespace pfem::motion {

// How much one DDM parameter moves a signal's constants (d constant / d parameter).
struct SignalSeed {
  double stroke = 0.0, period = 0.0, height = 0.0, scale = 0.0;
};

// A value and its derivative along one parameter.
struct Sensitive {
  double value = 0.0, derivative = 0.0;
};

struct Signal {
  enum class Kind { kSinusoid, kSolitary, kTable };
  Kind kind = Kind::kSinusoid;
  double stroke = 0.0, period = 1.0, ramp = 0.0;  // sinusoid
  double height = 0.0, depth = 1.0, gravity = 9.81;  // solitary (gravity: |g| of the model)
  std::vector<double> times, values;  // table
  bool cubic = false;
  double scale = 1.0;
  std::vector<double> curvatures;  // the natural cubic spline's second derivatives (prepare())

  // Fills the spline of a cubic table; call once after setting the table.
  void prepare();
  // s(t) [m] and its derivative along seed.
  Sensitive displacement(double t, const SignalSeed& seed) const;
};

struct WallMotion {
  bool flap = false;
  double direction_x = 1.0, direction_y = 0.0;  // piston
  double hinge_x = 0.0, hinge_y = 0.0, arm = 1.0;  // flap
  Signal signal;
  std::vector<int> nodes;  // the wall's node indices (corners and ends included)
  std::vector<SignalSeed> seeds;  // one per DDM parameter
};

// Where the rigid motion at displacement s puts the point (x0, y0) of the wall at rest, and the
// derivative of that place along ds; also the image of a direction (tx, ty) (for a flap, turned
// by the same rotation).
struct Placement {
  double x = 0.0, y = 0.0;    // the point
  double dx = 0.0, dy = 0.0;  // its derivative
  double tx = 0.0, ty = 0.0;    // the direction
  double dtx = 0.0, dty = 0.0;  // its derivative
};
Placement place(const WallMotion& m, const Sensitive& s, double x0, double y0, double tx = 0.0, double ty = 0.0);

}  // namespace pfem::motion
