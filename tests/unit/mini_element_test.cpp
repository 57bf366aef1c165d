// Independent check of the closed-form MINI triangle (engine/fluid/mini_element.*, theory §3,
// eqs. (53)-(63)) against numerical quadrature of the integral forms of theory §2:
//
//   M  = ∫ rho Nv^T Nv t        K = ∫ B^T D B t          G = ∫ B^T m Np t
//   F  = ∫ rho Nv^T b t         Mp = rowsum ∫ (1/kappa) Np^T Np t
//
// with N_a = L_a (corners), N4 = 27 L1 L2 L3 (bubble), velocity dofs (v1x v1y v2x v2y v3x v3y
// vbx vby), Np = [L1 L2 L3], strain rate B rows (exx, eyy, gxy = dvx/dy + dvy/dx),
// D = mu [[4/3, -2/3, 0], [-2/3, 4/3, 0], [0, 0, 1]], m = [1 1 0]^T.
//
// The reference integrals are computed here from scratch, in long double: a Gauss-Legendre
// product rule through the collapsed (Duffy) map of the reference triangle, the barycentric
// gradients from the inverse Jacobian of the affine map (not from the c_a, d_a of the code
// under test), and the bubble gradient by the chain rule through the barycentrics. Every
// closed-form matrix must match to 1e-12 relative to its largest entry.
//
// Further checks on the closed forms: invariance under rigid motion of the triangle
// (translation + rotation), the rigid-body null space of K, the divergence operator G^T,
// and the behaviour on clockwise input (pinned below).

#include "engine/fluid/mini_element.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using pfem::fluid::FluidConstants;
using pfem::fluid::Mat8;
using pfem::fluid::Mat83;
using pfem::fluid::MiniMatrices;
using pfem::fluid::TriangleGeometry;
using pfem::fluid::Vec3;
using pfem::fluid::Vec8;

using Real = long double;
using RMat8 = Eigen::Matrix<Real, 8, 8>;
using RMat83 = Eigen::Matrix<Real, 8, 3>;
using RMat3 = Eigen::Matrix<Real, 3, 3>;
using RVec8 = Eigen::Matrix<Real, 8, 1>;
using RVec3 = Eigen::Matrix<Real, 3, 1>;

constexpr double kTol = 1e-12;   // relative to the largest entry of the reference matrix
constexpr int kGaussPoints = 7;  // per direction: exact for polynomials of degree <= 12

struct Tri {
  std::array<double, 3> x{}, y{};
};

struct Params {
  double rho = 1.0, mu = 1.0, kappa = 1.0, t = 1.0, bx = 0.0, by = 0.0;
};

std::string describe(const Tri& tri, const Params& p) {
  std::ostringstream s;
  s.precision(17);
  s << "triangle (" << tri.x[0] << ", " << tri.y[0] << ") (" << tri.x[1] << ", " << tri.y[1]
    << ") (" << tri.x[2] << ", " << tri.y[2] << "), rho=" << p.rho << " mu=" << p.mu
    << " kappa=" << p.kappa << " t=" << p.t << " b=(" << p.bx << ", " << p.by << ")";
  return s.str();
}

// Reproducible across standard libraries: the engine is specified by the standard, the
// conversion to [0, 1) is done here (std::uniform_real_distribution is not portable).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : gen_(seed) {}
  double uniform(double lo, double hi) {
    const double u = static_cast<double>(gen_() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * u;
  }
  double log_uniform(double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  }

 private:
  std::mt19937_64 gen_;
};

// ---------------------------------------------------------------------------------------
// Quadrature
// ---------------------------------------------------------------------------------------

// n-point Gauss-Legendre rule on [0, 1] (Newton iteration on P_n, long double).
std::vector<std::pair<Real, Real>> gauss_legendre_01(int n) {
  std::vector<std::pair<Real, Real>> rule;
  const Real pi = std::numbers::pi_v<Real>;
  for (int i = 1; i <= n; ++i) {
    Real x = std::cos(pi * (static_cast<Real>(i) - 0.25L) / (static_cast<Real>(n) + 0.5L));
    Real dp = 0.0L;
    for (int iter = 0; iter < 100; ++iter) {
      Real p0 = 1.0L, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const Real p2 = ((2.0L * k - 1.0L) * x * p1 - (k - 1.0L) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0L);
      const Real dx = p1 / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-19L) break;
    }
    const Real w = 2.0L / ((1.0L - x * x) * dp * dp);
    rule.emplace_back((x + 1.0L) / 2.0L, w / 2.0L);
  }
  return rule;
}

// A point of the reference triangle {xi, eta >= 0, xi + eta <= 1} in barycentrics
// (L1 = 1 - xi - eta, L2 = xi, L3 = eta) and its weight; the weights sum to 1/2.
struct QuadPoint {
  std::array<Real, 3> L;
  Real w;
};

// Collapsed map xi = u, eta = (1 - u) v, d(xi, eta) = (1 - u) du dv. A monomial of total
// degree p becomes degree <= p + 1 in u and <= p in v: n points integrate p <= 2n - 2.
std::vector<QuadPoint> triangle_rule(int n) {
  const auto gl = gauss_legendre_01(n);
  std::vector<QuadPoint> rule;
  for (const auto& [u, wu] : gl) {
    for (const auto& [v, wv] : gl) {
      const Real xi = u, eta = (1.0L - u) * v;
      rule.push_back({{1.0L - xi - eta, xi, eta}, wu * wv * (1.0L - u)});
    }
  }
  return rule;
}

const std::vector<QuadPoint>& rule() {
  static const std::vector<QuadPoint> r = triangle_rule(kGaussPoints);
  return r;
}

Real factorial(int n) {
  Real f = 1.0L;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

// ---------------------------------------------------------------------------------------
// Reference integrals over the physical triangle (true area, |det J|)
// ---------------------------------------------------------------------------------------

struct Reference {
  RMat8 M = RMat8::Zero();
  RMat8 K = RMat8::Zero();
  RMat83 G = RMat83::Zero();
  RVec8 F = RVec8::Zero();
  RVec3 Mp = RVec3::Zero();
};

// Barycentric gradients from the inverse Jacobian of x = x1 + (x2 - x1) xi + (x3 - x1) eta.
struct Affine {
  Real det;                  // det J = twice the signed area
  std::array<Real, 3> Lx, Ly;  // dL_a/dx, dL_a/dy
};

Affine affine(const Tri& tri) {
  const Real j11 = static_cast<Real>(tri.x[1]) - tri.x[0];
  const Real j12 = static_cast<Real>(tri.x[2]) - tri.x[0];
  const Real j21 = static_cast<Real>(tri.y[1]) - tri.y[0];
  const Real j22 = static_cast<Real>(tri.y[2]) - tri.y[0];
  Affine a{};
  a.det = j11 * j22 - j12 * j21;
  // Rows of J^-1 are grad(xi) = grad(L2) and grad(eta) = grad(L3).
  a.Lx[1] = j22 / a.det;
  a.Ly[1] = -j12 / a.det;
  a.Lx[2] = -j21 / a.det;
  a.Ly[2] = j11 / a.det;
  a.Lx[0] = -a.Lx[1] - a.Lx[2];
  a.Ly[0] = -a.Ly[1] - a.Ly[2];
  return a;
}

Reference integrate(const Tri& tri, const Params& p) {
  const Affine af = affine(tri);
  const Real jac = std::fabs(af.det);  // |J|: the integral over the physical triangle
  const Real rho = p.rho, mu = p.mu, kappa = p.kappa, t = p.t;

  Eigen::Matrix<Real, 3, 3> D;
  D << 4.0L / 3.0L, -2.0L / 3.0L, 0.0L, -2.0L / 3.0L, 4.0L / 3.0L, 0.0L, 0.0L, 0.0L, 1.0L;
  D *= mu;
  const Eigen::Matrix<Real, 3, 1> m(1.0L, 1.0L, 0.0L);
  const Eigen::Matrix<Real, 2, 1> b(p.bx, p.by);

  Reference r;
  RMat3 Mp_consistent = RMat3::Zero();
  for (const QuadPoint& q : rule()) {
    const auto& L = q.L;
    // Shape functions and their gradients; the bubble by the chain rule.
    std::array<Real, 4> N{L[0], L[1], L[2], 27.0L * L[0] * L[1] * L[2]};
    std::array<Real, 4> Nx{af.Lx[0], af.Lx[1], af.Lx[2], 0.0L};
    std::array<Real, 4> Ny{af.Ly[0], af.Ly[1], af.Ly[2], 0.0L};
    Nx[3] = 27.0L * (af.Lx[0] * L[1] * L[2] + L[0] * af.Lx[1] * L[2] + L[0] * L[1] * af.Lx[2]);
    Ny[3] = 27.0L * (af.Ly[0] * L[1] * L[2] + L[0] * af.Ly[1] * L[2] + L[0] * L[1] * af.Ly[2]);

    Eigen::Matrix<Real, 2, 8> Nv = Eigen::Matrix<Real, 2, 8>::Zero();
    Eigen::Matrix<Real, 3, 8> B = Eigen::Matrix<Real, 3, 8>::Zero();
    for (int a = 0; a < 4; ++a) {
      Nv(0, 2 * a) = N[a];
      Nv(1, 2 * a + 1) = N[a];
      B(0, 2 * a) = Nx[a];
      B(1, 2 * a + 1) = Ny[a];
      B(2, 2 * a) = Ny[a];
      B(2, 2 * a + 1) = Nx[a];
    }
    const Eigen::Matrix<Real, 1, 3> Np(L[0], L[1], L[2]);

    const Real dw = q.w * jac * t;
    r.M += rho * Nv.transpose() * Nv * dw;
    r.K += B.transpose() * D * B * dw;
    r.G += B.transpose() * m * Np * dw;
    r.F += rho * Nv.transpose() * b * dw;
    Mp_consistent += Np.transpose() * Np / kappa * dw;
  }
  r.Mp = Mp_consistent.rowwise().sum();  // lumped: row sums
  return r;
}

// ---------------------------------------------------------------------------------------
// Code under test
// ---------------------------------------------------------------------------------------

MiniMatrices closed_form(const Tri& tri, const Params& p) {
  const TriangleGeometry g = pfem::fluid::triangle_geometry(tri.x, tri.y);
  MiniMatrices out;
  out.M.setConstant(std::nan(""));
  out.K.setConstant(std::nan(""));
  out.G.setConstant(std::nan(""));  // every entry must be written by the code under test
  out.F.setConstant(std::nan(""));
  out.Mp.setConstant(std::nan(""));
  pfem::fluid::mini_matrices(g, FluidConstants{p.rho, p.mu, p.kappa}, p.t, p.bx, p.by, out);
  return out;
}

// |got - want|_max <= tol * |want|_max (NaN fails).
template <class A, class B>
::testing::AssertionResult Close(const Eigen::MatrixBase<A>& got, const Eigen::MatrixBase<B>& want,
                                 double tol = kTol) {
  const Eigen::MatrixXd g = got.template cast<double>();
  const Eigen::MatrixXd w = want.template cast<double>();
  const double scale = w.cwiseAbs().maxCoeff();
  const double err = (g - w).cwiseAbs().maxCoeff();
  if (scale > 0.0 && err <= tol * scale) return ::testing::AssertionSuccess();
  std::ostringstream s;
  s.precision(17);
  s << "max|diff| = " << err << ", max|want| = " << scale << ", relative " << err / scale
    << " > " << tol << "\ngot:\n"
    << g << "\nwant:\n"
    << w << "\ndiff:\n"
    << (g - w);
  return ::testing::AssertionFailure() << s.str();
}

// |v|_max <= tol * scale (for vectors that must vanish).
template <class A>
::testing::AssertionResult Vanishes(const Eigen::MatrixBase<A>& v, double scale,
                                    double tol = kTol) {
  const double err = v.cwiseAbs().maxCoeff();
  if (err <= tol * scale) return ::testing::AssertionSuccess();
  std::ostringstream s;
  s.precision(17);
  s << "max|v| = " << err << " > " << tol << " * " << scale << "\nv:\n" << v;
  return ::testing::AssertionFailure() << s.str();
}

void expect_matches_quadrature(const Tri& tri, const Params& p, double sign = 1.0) {
  const MiniMatrices c = closed_form(tri, p);
  const Reference r = integrate(tri, p);
  const std::string what = describe(tri, p);
  EXPECT_TRUE(Close(c.M, sign * r.M)) << "M, " << what;
  EXPECT_TRUE(Close(c.K, sign * r.K)) << "K, " << what;
  EXPECT_TRUE(Close(c.G, sign * r.G)) << "G, " << what;
  EXPECT_TRUE(Close(c.F, sign * r.F)) << "F, " << what;
  EXPECT_TRUE(Close(c.Mp, sign * r.Mp)) << "Mp, " << what;
}

Params random_params(Rng& rng) {
  Params p;
  p.rho = rng.log_uniform(1.0, 1e4);
  p.mu = rng.log_uniform(1e-4, 10.0);
  p.kappa = rng.log_uniform(1e4, 1e10);
  p.t = rng.log_uniform(1e-3, 1.0);
  p.bx = rng.uniform(-10.0, 10.0);
  p.by = rng.uniform(-10.0, 10.0);
  return p;
}

double signed_double_area(const Tri& tri) {
  return (tri.x[1] - tri.x[0]) * (tri.y[2] - tri.y[0]) -
         (tri.x[2] - tri.x[0]) * (tri.y[1] - tri.y[0]);
}

// A counter-clockwise triangle with vertices in [-3, 3]^2, not degenerate (random shapes;
// thin ones are tested on purpose separately).
Tri random_ccw_triangle(Rng& rng) {
  for (;;) {
    Tri tri;
    for (int a = 0; a < 3; ++a) {
      tri.x[a] = rng.uniform(-3.0, 3.0);
      tri.y[a] = rng.uniform(-3.0, 3.0);
    }
    double longest2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3;
      const double dx = tri.x[b] - tri.x[a], dy = tri.y[b] - tri.y[a];
      longest2 = std::max(longest2, dx * dx + dy * dy);
    }
    const double A = signed_double_area(tri);
    if (std::fabs(A) < 0.05 * longest2) continue;
    if (A < 0.0) {
      std::swap(tri.x[1], tri.x[2]);
      std::swap(tri.y[1], tri.y[2]);
    }
    return tri;
  }
}

Tri rigid_motion(const Tri& tri, double angle, double sx, double sy) {
  const double cs = std::cos(angle), sn = std::sin(angle);
  Tri out;
  for (int a = 0; a < 3; ++a) {
    out.x[a] = cs * tri.x[a] - sn * tri.y[a] + sx;
    out.y[a] = sn * tri.x[a] + cs * tri.y[a] + sy;
  }
  return out;
}

// Block-diagonal 8x8 rotation: v' = R v rotates every nodal velocity (corners and bubble).
Mat8 block_rotation(double angle) {
  const double cs = std::cos(angle), sn = std::sin(angle);
  Mat8 R = Mat8::Zero();
  for (int a = 0; a < 4; ++a) {
    R(2 * a, 2 * a) = cs;
    R(2 * a, 2 * a + 1) = -sn;
    R(2 * a + 1, 2 * a) = sn;
    R(2 * a + 1, 2 * a + 1) = cs;
  }
  return R;
}

// Nodal velocities of the linear field v(x, y) = (a0 + a1 x + a2 y, b0 + b1 x + b2 y) at the
// corners, with zero bubble velocity.
Vec8 linear_field(const Tri& tri, double a0, double a1, double a2, double b0, double b1,
                  double b2) {
  Vec8 v = Vec8::Zero();
  for (int a = 0; a < 3; ++a) {
    v(2 * a) = a0 + a1 * tri.x[a] + a2 * tri.y[a];
    v(2 * a + 1) = b0 + b1 * tri.x[a] + b2 * tri.y[a];
  }
  return v;
}

// A thin triangle of aspect ratio ~1000 (height 1e-3 on a unit base), rotated and moved off
// the origin; and a flat obtuse one (angle close to 180 degrees at the middle vertex).
Tri thin_sliver() {
  Tri base;
  base.x = {0.0, 1.0, 0.37};
  base.y = {0.0, 0.0, 1e-3};
  return rigid_motion(base, 0.7, 0.25, -0.4);
}

Tri flat_obtuse() {
  Tri base;
  base.x = {0.0, 1.0, 2.0};
  base.y = {0.0, 2e-3, 0.0};  // clockwise as given; flipped below
  std::swap(base.x[1], base.x[2]);
  std::swap(base.y[1], base.y[2]);
  return rigid_motion(base, -1.9, -1.3, 2.2);
}

// ---------------------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------------------

// The quadrature itself: ∫_ref L1^a L2^b L3^c = a! b! c! / (a + b + c + 2)! (reference
// triangle, twice the area = 1), for every total degree up to 12 (>= 8 is needed: M_44 is
// degree 6).
TEST(MiniElementQuadrature, IntegratesBarycentricMonomialsExactly) {
  for (int a = 0; a <= 12; ++a) {
    for (int b = 0; a + b <= 12; ++b) {
      for (int c = 0; a + b + c <= 12; ++c) {
        Real sum = 0.0L;
        for (const QuadPoint& q : rule()) {
          sum += q.w * std::pow(q.L[0], a) * std::pow(q.L[1], b) * std::pow(q.L[2], c);
        }
        const Real exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 2);
        EXPECT_LT(std::fabs(static_cast<double>((sum - exact) / exact)), 1e-15)
            << "a=" << a << " b=" << b << " c=" << c << " quadrature " << static_cast<double>(sum)
            << " exact " << static_cast<double>(exact);
      }
    }
  }
}

// triangle_geometry (53)-(54): A is twice the signed area, and (c_a, d_a)/A is the gradient of
// the barycentric L_a (compared with the inverse Jacobian of the affine map).
TEST(MiniElement, GeometryGivesTwiceSignedAreaAndBarycentricGradients) {
  Rng rng(20240601);
  std::vector<Tri> tris{thin_sliver(), flat_obtuse()};
  for (int i = 0; i < 20; ++i) tris.push_back(random_ccw_triangle(rng));
  Tri cw = tris.back();
  std::swap(cw.x[0], cw.x[1]);
  std::swap(cw.y[0], cw.y[1]);
  tris.push_back(cw);
  for (const Tri& tri : tris) {
    const TriangleGeometry g = pfem::fluid::triangle_geometry(tri.x, tri.y);
    const Affine af = affine(tri);
    const std::string what = describe(tri, Params{});
    EXPECT_NEAR(g.A, static_cast<double>(af.det), 1e-12 * std::fabs(g.A)) << what;
    Eigen::Matrix<double, 3, 2> got, want;
    for (int a = 0; a < 3; ++a) {
      got(a, 0) = g.c[a] / g.A;
      got(a, 1) = g.d[a] / g.A;
      want(a, 0) = static_cast<double>(af.Lx[a]);
      want(a, 1) = static_cast<double>(af.Ly[a]);
    }
    EXPECT_TRUE(Close(got, want)) << what;
  }
  EXPECT_LT(pfem::fluid::triangle_geometry(cw.x, cw.y).A, 0.0);
}

// Every closed-form matrix against quadrature, on random counter-clockwise triangles with
// random material constants, thickness and body force.
TEST(MiniElement, MatchesQuadratureOnRandomTriangles) {
  Rng rng(0x5eed1234abcdULL);
  for (int i = 0; i < 25; ++i) {
    const Tri tri = random_ccw_triangle(rng);
    const Params p = random_params(rng);
    SCOPED_TRACE("random triangle #" + std::to_string(i));
    expect_matches_quadrature(tri, p);
  }
}

// The same on a sliver of aspect ratio ~1000 and a flat triangle with an angle near 180
// degrees (both rotated and off the origin), three sets of random constants each.
TEST(MiniElement, MatchesQuadratureOnBadlyShapedTriangles) {
  Rng rng(77);
  for (const Tri& tri : {thin_sliver(), flat_obtuse()}) {
    ASSERT_GT(signed_double_area(tri), 0.0);
    for (int i = 0; i < 3; ++i) expect_matches_quadrature(tri, random_params(rng));
  }
}

// Clockwise input. The closed forms (56)-(63) use the SIGNED A (twice the signed area) where
// the integrals have |A|: M, F, Mp are proportional to A, K to 1/A, and G is independent of
// A while its integrand (c_a/A) L_b flips sign with A. So for a clockwise triangle EVERY
// matrix comes out as exactly -1 times the true integral over that triangle (negative mass
// and pressure mass, negative semi-definite K, G^T v = minus the true divergence). The engine
// always passes counter-clockwise triangles; this test pins that behaviour.
TEST(MiniElement, ClockwiseTriangleGivesNegatedIntegrals) {
  Rng rng(4242);
  for (int i = 0; i < 5; ++i) {
    const Tri ccw = random_ccw_triangle(rng);
    Tri cw = ccw;  // same triangle, nodes 2 and 3 swapped
    std::swap(cw.x[1], cw.x[2]);
    std::swap(cw.y[1], cw.y[2]);
    ASSERT_LT(pfem::fluid::triangle_geometry(cw.x, cw.y).A, 0.0);
    const Params p = random_params(rng);
    SCOPED_TRACE("clockwise triangle #" + std::to_string(i));
    expect_matches_quadrature(cw, p, -1.0);

    // Equivalently: minus the counter-clockwise element's matrices with nodes 2, 3 permuted.
    const MiniMatrices c = closed_form(cw, p), o = closed_form(ccw, p);
    Mat8 P8 = Mat8::Zero();  // P8(i, j) = 1 when cw dof i is ccw dof j
    const int node_map[4] = {0, 2, 1, 3};
    for (int a = 0; a < 4; ++a) {
      P8(2 * a, 2 * node_map[a]) = 1.0;
      P8(2 * a + 1, 2 * node_map[a] + 1) = 1.0;
    }
    Eigen::Matrix3d P3 = Eigen::Matrix3d::Zero();
    P3(0, 0) = P3(1, 2) = P3(2, 1) = 1.0;
    EXPECT_TRUE(Close(c.M, -(P8 * o.M * P8.transpose())));
    EXPECT_TRUE(Close(c.K, -(P8 * o.K * P8.transpose())));
    EXPECT_TRUE(Close(c.G, -(P8 * o.G * P3.transpose())));
    EXPECT_TRUE(Close(c.F, -(P8 * o.F)));
    EXPECT_TRUE(Close(c.Mp, -(P3 * o.Mp)));
    EXPECT_LT(c.M(0, 0), 0.0);
    EXPECT_LT(c.Mp(0), 0.0);
    EXPECT_LT(c.K(6, 6), 0.0);

    // Uniform expansion v = (x, y): G^T v = A t / 3 = -(2 area t / 3) per corner.
    const double area = 0.5 * std::fabs(signed_double_area(cw));
    const Vec3 div = c.G.transpose() * linear_field(cw, 0, 1, 0, 0, 0, 1);
    EXPECT_TRUE(Close(div, Vec3::Constant(-2.0 * area * p.t / 3.0)));
  }
}

// Rigid motion x' = Q x + s of the triangle, velocities v' = R v (R = diag(Q, Q, Q, Q)):
// M, Mp unchanged, F(Q b) = R F(b), K' = R K R^T, G' = R G (i.e. K = R^T K' R, G = R^T G').
//
// Shifts: up to 5 for the random triangles (size ~1-6), but the two thin ones (twice-area
// ~1e-3) are first centred on the origin and moved by at most 0.25. The reason is floating
// point, not the formulas: A from the expanded form (53) x2 y3 - x3 y2 + ... cancels products
// of size |x|^2 down to A, so its rounding error grows like eps |x|^2 / A. For the sliver
// moved by ~5 the closed-form A is off by ~2e-12 relative from the exact area of its own
// (double) coordinates (~7e-8 at a shift of 1000), and rounding the moved coordinates alone
// changes the true area by ~3e-13.
TEST(MiniElement, RigidMotionInvariance) {
  Rng rng(99);
  std::vector<Tri> tris{thin_sliver(), flat_obtuse()};
  for (int i = 0; i < 6; ++i) tris.push_back(random_ccw_triangle(rng));
  const double angles[] = {0.0, 0.3, std::numbers::pi / 2, 2.0, -2.7, std::numbers::pi};
  for (std::size_t k = 0; k < tris.size(); ++k) {
    Tri tri = tris[k];
    const bool thin = k < 2;
    if (thin) {
      const double xc = (tri.x[0] + tri.x[1] + tri.x[2]) / 3.0;
      const double yc = (tri.y[0] + tri.y[1] + tri.y[2]) / 3.0;
      tri = rigid_motion(tri, 0.0, -xc, -yc);
    }
    const double shift = thin ? 0.25 : 5.0;
    const Params p = random_params(rng);
    const MiniMatrices m0 = closed_form(tri, p);
    for (double angle : angles) {
      const double sx = rng.uniform(-shift, shift), sy = rng.uniform(-shift, shift);
      const Tri moved = rigid_motion(tri, angle, sx, sy);
      Params pr = p;  // the body force rotates with the triangle
      pr.bx = std::cos(angle) * p.bx - std::sin(angle) * p.by;
      pr.by = std::sin(angle) * p.bx + std::cos(angle) * p.by;
      const MiniMatrices m1 = closed_form(moved, pr);
      const Mat8 R = block_rotation(angle);
      const std::string what = describe(tri, p) + ", angle " + std::to_string(angle);
      EXPECT_TRUE(Close(m1.M, m0.M)) << "M " << what;
      EXPECT_TRUE(Close(m1.Mp, m0.Mp)) << "Mp " << what;
      EXPECT_TRUE(Close(m1.F, R * m0.F)) << "F " << what;
      EXPECT_TRUE(Close(m1.K, R * m0.K * R.transpose())) << "K " << what;
      EXPECT_TRUE(Close(R.transpose() * m1.K * R, m0.K)) << "K " << what;
      EXPECT_TRUE(Close(m1.G, R * m0.G)) << "G " << what;
      EXPECT_NEAR(m1.F.norm(), m0.F.norm(), kTol * m0.F.norm()) << "|F| " << what;
    }
  }
}

// K is symmetric positive semi-definite with exactly the three rigid motions (two
// translations and the rotation, corners moving rigidly, zero bubble) in its null space.
TEST(MiniElement, ViscousMatrixAnnihilatesRigidMotionsOnly) {
  Rng rng(31337);
  std::vector<Tri> tris{thin_sliver(), flat_obtuse()};
  for (int i = 0; i < 8; ++i) tris.push_back(random_ccw_triangle(rng));
  for (const Tri& tri : tris) {
    const Params p = random_params(rng);
    const MiniMatrices m = closed_form(tri, p);
    const std::string what = describe(tri, p);
    EXPECT_TRUE(Close(m.K.transpose(), m.K)) << what;

    const double kmax = m.K.cwiseAbs().maxCoeff();
    const double x0 = rng.uniform(-2, 2), y0 = rng.uniform(-2, 2), w = rng.uniform(0.5, 2.0);
    const Vec8 modes[] = {
        linear_field(tri, 1, 0, 0, 0, 0, 0),              // translation x
        linear_field(tri, 0, 0, 0, 1, 0, 0),              // translation y
        linear_field(tri, 0, 0, -1, 0, 1, 0),             // rotation about the origin
        linear_field(tri, w * y0, 0, -w, -w * x0, w, 0),  // rotation about (x0, y0)
    };
    const double gmax = m.G.cwiseAbs().maxCoeff();
    for (const Vec8& v : modes) {
      const double vmax = v.cwiseAbs().maxCoeff();
      EXPECT_TRUE(Vanishes(m.K * v, kmax * vmax)) << "K of a rigid motion, " << what;
      EXPECT_TRUE(Vanishes(m.G.transpose() * v, gmax * vmax)) << "G^T of a rigid motion, " << what;
    }

    // Spectrum: 3 zero eigenvalues (rigid), 5 strictly positive.
    const Eigen::SelfAdjointEigenSolver<Mat8> eig(m.K);
    const Vec8 ev = eig.eigenvalues();  // ascending
    for (int i = 0; i < 3; ++i) EXPECT_LT(std::fabs(ev(i)), 1e-11 * ev(7)) << what;
    EXPECT_GT(ev(3), 1e-9 * ev(7)) << what;

    // A non-rigid linear field (pure shear, zero bubble) is not annihilated.
    const Vec8 shear = linear_field(tri, 0, 0, 1, 0, 1, 0);
    EXPECT_GT((m.K * shear).cwiseAbs().maxCoeff(), 1e-6 * kmax * shear.cwiseAbs().maxCoeff());
  }
}

// G^T v is the element's weighted divergence ∫ Np^T div(v) t: zero for rigid motions (above),
// and for the uniform expansion v = (x - x0, y - y0) (div = 2, zero bubble) exactly
// 2 * area * t / 3 at each corner, area computed independently.
TEST(MiniElement, DivergenceOfUniformExpansion) {
  Rng rng(2718);
  std::vector<Tri> tris{thin_sliver(), flat_obtuse()};
  for (int i = 0; i < 10; ++i) tris.push_back(random_ccw_triangle(rng));
  for (const Tri& tri : tris) {
    const Params p = random_params(rng);
    const MiniMatrices m = closed_form(tri, p);
    const double area = 0.5 * std::fabs(signed_double_area(tri));
    const double x0 = rng.uniform(-3, 3), y0 = rng.uniform(-3, 3);
    const Vec3 expected = Vec3::Constant(2.0 * area * p.t / 3.0);
    EXPECT_TRUE(Close(m.G.transpose() * linear_field(tri, 0, 1, 0, 0, 0, 1), expected))
        << describe(tri, p);
    EXPECT_TRUE(Close(m.G.transpose() * linear_field(tri, -x0, 1, 0, -y0, 0, 1), expected))
        << describe(tri, p);
    // A pure x-stretch v = (x, 0): div = 1.
    EXPECT_TRUE(Close(m.G.transpose() * linear_field(tri, 0, 1, 0, 0, 0, 0), expected / 2.0))
        << describe(tri, p);
  }
}

// step_geometry: over a step x = x_n + dt v the triangle's (twice) area changes by exactly
// dt (c_m . vx + d_m . vy) with the midpoint's c, d (its mass balance keeps the area), and the
// momentum balance's geometry is the end's.
TEST(MiniElement, StepGeometryTakesTheMassBalanceAtTheMidpoint) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::array<double, 3> xn{0.0, 0.01, 0.002}, yn{0.0, 0.001, 0.009}, vx, vy, x, y;
    for (int a = 0; a < 3; ++a) vx[a] = u(rng), vy[a] = u(rng);
    const double dt = 2e-3;
    for (int a = 0; a < 3; ++a) x[a] = xn[a] + dt * vx[a], y[a] = yn[a] + dt * vy[a];
    const TriangleGeometry g = pfem::fluid::step_geometry(xn, yn, vx, vy, dt);
    const TriangleGeometry end = pfem::fluid::triangle_geometry(x, y);
    EXPECT_EQ(g.A, end.A);
    EXPECT_EQ(g.c, end.c);
    double rate = 0.0;
    for (int a = 0; a < 3; ++a) rate += g.cm[a] * vx[a] + g.dm[a] * vy[a];
    const double change = end.A - pfem::fluid::triangle_geometry(xn, yn).A;
    EXPECT_NEAR(change, dt * rate, 1e-15 * std::abs(end.A)) << "trial " << trial;
    EXPECT_GT(std::abs(change), 1e-6 * std::abs(end.A));  // the step does change the area
  }
}

}  // namespace
