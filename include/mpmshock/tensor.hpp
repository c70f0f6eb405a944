// Small fixed-size vectors and tensors of a D-dimensional run (D = 2: plane strain in x, y;
// D = 3). One code path serves both dimensions: the physics is written with these types and loops
// over D; only the few operations whose 2D form is the plane-strain reduction of the 3D one
// (deviators, spin, determinant) are spelled out per dimension.
//
// Sums are written first-term-first (s = a0 b0; s += a1 b1; ...), the same expression a written
// out 2D formula compiles to, so results are bit for bit those of the hand-written 2D code.
#pragma once

#include <cmath>

#include "mpmshock/number.hpp"

namespace mpmshock {

// T: the number type, a double or four points' Lanes (number.hpp).
template <int D, class T = double>
struct Vec {
  static_assert(D == 2 || D == 3, "mpmshock runs in 2 or 3 dimensions");
  T c[D];
  T& operator[](int i) { return c[i]; }
  const T& operator[](int i) const { return c[i]; }
};

// |v|
template <int D>
inline double speed(const Vec<D>& v) {
  if constexpr (D == 2) return std::hypot(v[0], v[1]);
  else return std::hypot(v[0], v[1], v[2]);
}

// a . b
template <int D>
inline double dot(const Vec<D>& a, const Vec<D>& b) {
  double s = a[0] * b[0];
  for (int d = 1; d < D; ++d) s += a[d] * b[d];
  return s;
}

// A D x D matrix, row i, column j: M(i, j). Deformation gradient F[i][j] = dx_i/dX_j, velocity
// gradient L[i][j] = dv_i/dx_j. T: the number type, a double or four points' Lanes (number.hpp);
// the point update computes with both, everything else with doubles.
template <int D, class T = double>
struct Mat {
  T c[D][D];
  T& operator()(int i, int j) { return c[i][j]; }
  const T& operator()(int i, int j) const { return c[i][j]; }
  static Mat identity() {
    Mat m{};
    for (int i = 0; i < D; ++i) m.c[i][i] = m.c[i][i] + 1.0;
    return m;
  }
};

// tr M
template <int D, class T>
inline T trace(const Mat<D, T>& m) {
  T t = m(0, 0);
  for (int i = 1; i < D; ++i) t += m(i, i);
  return t;
}

// det M; for F, J = V / V0 (plane strain: F_zz = 1).
template <class T>
inline T det(const Mat<2, T>& m) { return m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0); }
template <class T>
inline T det(const Mat<3, T>& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

// A B
template <int D, class T>
inline Mat<D, T> product(const Mat<D, T>& a, const Mat<D, T>& b) {
  Mat<D, T> r;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      T s = a(i, 0) * b(0, j);
      for (int k = 1; k < D; ++k) s += a(i, k) * b(k, j);
      r(i, j) = s;
    }
  return r;
}

// A trace-free symmetric 3x3 tensor (deviatoric stress s, back stress alpha). The zz component is
// not stored but is -(xx + yy): exact in exact arithmetic, and the same rule in both dimensions.
// In plane strain (D = 2) yz = zx = 0 and three numbers carry it; in 3D five.
template <int D, class T = double>
struct Deviator;

template <class T>
struct Deviator<2, T> {
  T xx{}, yy{}, xy{};
  T zz() const { return -(xx + yy); }
  T yz() const { return T{}; }
  T zx() const { return T{}; }
  // ||a||^2 = a:a over the full 3x3 tensor.
  T norm2() const { return xx * xx + yy * yy + zz() * zz() + 2.0 * xy * xy; }
};

template <class T>
struct Deviator<3, T> {
  T xx{}, yy{}, xy{}, yz_{}, zx_{};
  T zz() const { return -(xx + yy); }
  T yz() const { return yz_; }
  T zx() const { return zx_; }
  T norm2() const {
    return xx * xx + yy * yy + zz() * zz() + 2.0 * xy * xy + 2.0 * yz_ * yz_ + 2.0 * zx_ * zx_;
  }
};

template <class T>
inline Deviator<2, T> operator+(const Deviator<2, T>& a, const Deviator<2, T>& b) {
  return {a.xx + b.xx, a.yy + b.yy, a.xy + b.xy};
}
template <class T>
inline Deviator<2, T> operator-(const Deviator<2, T>& a, const Deviator<2, T>& b) {
  return {a.xx - b.xx, a.yy - b.yy, a.xy - b.xy};
}
template <class K, class T>
inline Deviator<2, T> operator*(const K& k, const Deviator<2, T>& a) { return {k * a.xx, k * a.yy, k * a.xy}; }
template <class T>
inline Deviator<3, T> operator+(const Deviator<3, T>& a, const Deviator<3, T>& b) {
  return {a.xx + b.xx, a.yy + b.yy, a.xy + b.xy, a.yz_ + b.yz_, a.zx_ + b.zx_};
}
template <class T>
inline Deviator<3, T> operator-(const Deviator<3, T>& a, const Deviator<3, T>& b) {
  return {a.xx - b.xx, a.yy - b.yy, a.xy - b.xy, a.yz_ - b.yz_, a.zx_ - b.zx_};
}
template <class K, class T>
inline Deviator<3, T> operator*(const K& k, const Deviator<3, T>& a) {
  return {k * a.xx, k * a.yy, k * a.xy, k * a.yz_, k * a.zx_};
}
// Lane by lane, a where the condition holds, else b (for a double: the condition is a bool).
template <class M, class T>
inline Deviator<2, T> choose(const M& where, const Deviator<2, T>& a, const Deviator<2, T>& b) {
  return {where ? a.xx : b.xx, where ? a.yy : b.yy, where ? a.xy : b.xy};
}
template <class M, class T>
inline Deviator<3, T> choose(const M& where, const Deviator<3, T>& a, const Deviator<3, T>& b) {
  return {where ? a.xx : b.xx, where ? a.yy : b.yy, where ? a.xy : b.xy, where ? a.yz_ : b.yz_, where ? a.zx_ : b.zx_};
}

// Equivalent (von Mises) stress sqrt(3/2) ||a||.
template <int D, class T>
inline T equivalent_stress(const Deviator<D, T>& a) {
  return square_root(1.5 * a.norm2());
}

// a : A for a deviator a and a D x D matrix A (the stress power s : L, the spin drops out).
template <class T>
inline T contract(const Deviator<2, T>& a, const Mat<2, T>& m) {
  return a.xx * m(0, 0) + a.yy * m(1, 1) + a.xy * (m(0, 1) + m(1, 0));
}
template <class T>
inline T contract(const Deviator<3, T>& a, const Mat<3, T>& m) {
  return a.xx * m(0, 0) + a.yy * m(1, 1) + a.zz() * m(2, 2) + a.xy * (m(0, 1) + m(1, 0)) +
         a.yz_ * (m(1, 2) + m(2, 1)) + a.zx_ * (m(2, 0) + m(0, 2));
}

// The velocity gradient split into what the stress update needs: the rate of deformation
// D = sym(L) and the spin W = skew(L). Plane strain: D_zz = 0 and W has one component W_xy.
template <int D, class T = double>
struct StrainRate;

template <class T>
struct StrainRate<2, T> {
  T xx, yy, xy;  // D
  T spin;        // W_xy = (L_xy - L_yx)/2
  T trace() const { return xx + yy; }
  T norm2() const { return xx * xx + yy * yy + 2.0 * xy * xy; }  // D : D
  Deviator<2, T> deviator() const {
    const T third = trace() / 3.0;
    return {xx - third, yy - third, xy};  // zz = -tr D/3, consistent with Deviator::zz()
  }
};

template <class T>
struct StrainRate<3, T> {
  T xx, yy, zz, xy, yz, zx;  // D
  T w_xy, w_yz, w_zx;        // W_ij = (L_ij - L_ji)/2
  T trace() const { return xx + yy + zz; }
  T norm2() const { return xx * xx + yy * yy + zz * zz + 2.0 * xy * xy + 2.0 * yz * yz + 2.0 * zx * zx; }
  Deviator<3, T> deviator() const {
    const T third = trace() / 3.0;
    return {xx - third, yy - third, xy, yz, zx};
  }
};

template <class T>
inline StrainRate<2, T> strain_rate(const Mat<2, T>& L) {
  return {L(0, 0), L(1, 1), 0.5 * (L(0, 1) + L(1, 0)), 0.5 * (L(0, 1) - L(1, 0))};
}
template <class T>
inline StrainRate<3, T> strain_rate(const Mat<3, T>& L) {
  return {L(0, 0),
          L(1, 1),
          L(2, 2),
          0.5 * (L(0, 1) + L(1, 0)),
          0.5 * (L(1, 2) + L(2, 1)),
          0.5 * (L(2, 0) + L(0, 2)),
          0.5 * (L(0, 1) - L(1, 0)),
          0.5 * (L(1, 2) - L(2, 1)),
          0.5 * (L(2, 0) - L(0, 2))};
}

// The rotation of a step with spin W: the Hughes-Winget (Cayley) form
// R = (I - W dt/2)^-1 (I + W dt/2), orthogonal for any dt (a rotated tensor keeps its norm to
// round-off) and second-order accurate against exp(W dt) (its angle is 2 atan(w dt/2)). The
// forward-Euler rate a += dt (W a - a W) would grow ||a|| by sqrt(1 + 4 (w dt)^2) every step.
template <int D, class T = double>
struct Rotation;

template <class T>
struct Rotation<2, T> {
  T c, s;  // R = [[c, s], [-s, c]]; no rotation about anything but z in plane strain
};
template <class T>
struct Rotation<3, T> {
  T r[3][3];
};

template <class T>
inline Rotation<2, T> spin_rotation(const StrainRate<2, T>& D, double dt) {
  const T t = 0.5 * dt * D.spin, inv = 1.0 / (1.0 + t * t);
  return {(1.0 - t * t) * inv, 2.0 * t * inv};
}
template <class T>
inline Rotation<3, T> spin_rotation(const StrainRate<3, T>& D, double dt) {
  // A = W dt/2 is skew; (I - A)^-1 (I + A) = I + 2/(1 + |a|^2) (A + A^2), |a|^2 = ||A||_F^2 / 2.
  const double h = 0.5 * dt;
  const T zero{};
  const T A[3][3] = {{zero, h * D.w_xy, -h * D.w_zx}, {-h * D.w_xy, zero, h * D.w_yz}, {h * D.w_zx, -h * D.w_yz, zero}};
  const T a2 = h * h * (D.w_xy * D.w_xy + D.w_yz * D.w_yz + D.w_zx * D.w_zx);
  const T k = 2.0 / (1.0 + a2);
  Rotation<3, T> R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      T A2{};
      for (int m = 0; m < 3; ++m) A2 += A[i][m] * A[m][j];
      R.r[i][j] = (i == j ? 1.0 : 0.0) + k * (A[i][j] + A2);
    }
  return R;
}

// R a R^T: a deviator carried along by the material's rotation (the Jaumann rate's spin part).
template <class T>
inline Deviator<2, T> rotate(const Deviator<2, T>& a, const Rotation<2, T>& R) {
  const T cc = R.c * R.c, ss = R.s * R.s, cs = R.c * R.s;
  return {cc * a.xx + 2.0 * cs * a.xy + ss * a.yy, ss * a.xx - 2.0 * cs * a.xy + cc * a.yy,
          cs * (a.yy - a.xx) + (cc - ss) * a.xy};
}
template <class T>
inline Deviator<3, T> rotate(const Deviator<3, T>& a, const Rotation<3, T>& R) {
  const T A[3][3] = {{a.xx, a.xy, a.zx()}, {a.xy, a.yy, a.yz()}, {a.zx(), a.yz(), a.zz()}};
  T RA[3][3], out[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      T s{};
      for (int m = 0; m < 3; ++m) s += R.r[i][m] * A[m][j];
      RA[i][j] = s;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      T s{};
      for (int m = 0; m < 3; ++m) s += RA[i][m] * R.r[j][m];
      out[i][j] = s;
    }
  return {out[0][0], out[1][1], out[0][1], out[1][2], out[2][0]};
}

}  // namespace mpmshock
