// The dot products and scaled additions of the solver's rows (private to physics/), added in Bullet's order.
#pragma once

#include <LinearMath/btScalar.h>

namespace car_sim {
namespace physics {

// acc + sum of a[i] b[i], added in index order as Bullet's loops add them (the same bits).
inline btScalar add_dot(btScalar acc, const btScalar* a, const btScalar* b, int n) {
  for (int i = 0; i < n; ++i) acc += a[i] * b[i];
  return acc;
}

// add_dot and the velocity update of a row side for the common sizes of a multibody (6 + dofs) known to the
// compiler: the loops unrolled, the same operations in the same order.
template <int N>
inline btScalar add_dot_fixed(btScalar acc, const btScalar* a, const btScalar* b) {
#pragma GCC unroll 16
  for (int i = 0; i < N; ++i) acc += a[i] * b[i];
  return acc;
}

inline btScalar add_dot_n(btScalar acc, const btScalar* a, const btScalar* b, int n) {
  switch (n) {
    case 7: return add_dot_fixed<7>(acc, a, b);
    case 8: return add_dot_fixed<8>(acc, a, b);
    case 9: return add_dot_fixed<9>(acc, a, b);
    case 10: return add_dot_fixed<10>(acc, a, b);
    case 11: return add_dot_fixed<11>(acc, a, b);
    case 12: return add_dot_fixed<12>(acc, a, b);
    default: return add_dot(acc, a, b, n);
  }
}

// v += u * delta, element by element
template <int N>
inline void add_scaled_fixed(btScalar* v, const btScalar* u, btScalar delta) {
#pragma GCC unroll 16
  for (int i = 0; i < N; ++i) v[i] += u[i] * delta;
}

inline void add_scaled_n(btScalar* v, const btScalar* u, btScalar delta, int n) {
  switch (n) {
    case 7: return add_scaled_fixed<7>(v, u, delta);
    case 8: return add_scaled_fixed<8>(v, u, delta);
    case 9: return add_scaled_fixed<9>(v, u, delta);
    case 10: return add_scaled_fixed<10>(v, u, delta);
    case 11: return add_scaled_fixed<11>(v, u, delta);
    case 12: return add_scaled_fixed<12>(v, u, delta);
    default:
      for (int i = 0; i < n; ++i) v[i] += u[i] * delta;
  }
}

}  // namespace physics
}  // namespace car_sim
