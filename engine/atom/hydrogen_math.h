#pragma once
// Hydrogen wave functions in atomic units (lengths in a0, Z = 1): the associated Laguerre and
// normalised associated Legendre recurrences, as MASAV_HD templates on the float type. The host
// builds the sampling tables from these in double (engine/atom/orbital_tables.cpp).
//
//   psi_nlm(r, theta, phi) = R_nl(r) Y_lm(theta, phi)
//   R_nl(r) = N_nl e^{-r/n} (2r/n)^l L_{n-l-1}^{2l+1}(2r/n),
//   N_nl^2 = (2/n)^3 (n-l-1)! / (2n (n+l)!)
//   |Y_lm|^2 = Pbar_l^|m|(cos theta)^2 (complex, e^{i m phi}), times 2 cos^2(m phi) (real, m > 0)
//   or 2 sin^2(|m| phi) (real, m < 0), with Pbar normalised so that 2 pi int Pbar^2 dx = 1.
#include "engine/core/hd.h"

namespace masav::hydrogen {

// Generalised Laguerre polynomial L_k^alpha(x), upward three-term recurrence (stable for x >= 0
// and the k <= 20 used here).
template <class T>
MASAV_HD inline T laguerre(int k, T alpha, T x) {
  if (k == 0) return T(1);
  T prev = T(1), cur = T(1) + alpha - x;
  for (int j = 1; j < k; ++j) {
    const T next = ((T(2 * j + 1) + alpha - x) * cur - (T(j) + alpha) * prev) / T(j + 1);
    prev = cur;
    cur = next;
  }
  return cur;
}

// Pbar_l^m(x) for 0 <= m <= l, |x| <= 1: the associated Legendre function normalised as in the
// spherical harmonics, Pbar = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!) P_l^m, by the standard stable
// recurrence in l at fixed m (no factorials, no overflow): Pbar_m^m from a product, then
// Pbar_l^m = a_lm (x Pbar_{l-1}^m - Pbar_{l-2}^m / a_{l-1,m}), a_lm = sqrt((4l^2-1)/(l^2-m^2)).
template <class T, class SqrtFn>
MASAV_HD inline T legendre_normalized(int l, int m, T x, SqrtFn sqrt_fn) {
  const T s = sqrt_fn(T(1) - x * x > T(0) ? T(1) - x * x : T(0));
  T pmm = T(0.28209479177387814347);  // 1 / sqrt(4 pi)
  for (int k = 1; k <= m; ++k) pmm *= -sqrt_fn(T(2 * k + 1) / T(2 * k)) * s;
  if (l == m) return pmm;
  T pm1 = x * sqrt_fn(T(2 * m + 3)) * pmm;  // l = m + 1
  if (l == m + 1) return pm1;
  T prev = pmm, cur = pm1;
  T a_prev = sqrt_fn(T(2 * m + 3));  // a_{m+1,m}
  for (int ll = m + 2; ll <= l; ++ll) {
    const T a = sqrt_fn(T(4 * ll * ll - 1) / T(ll * ll - m * m));
    const T next = a * (x * cur - prev / a_prev);
    prev = cur;
    cur = next;
    a_prev = a;
  }
  return cur;
}

// R_nl(r) given log N_nl (computed once on the host with lgamma) and an exp function.
template <class T, class ExpFn>
MASAV_HD inline T radial(int n, int l, T r, T log_norm, ExpFn exp_fn) {
  const T rho = T(2) * r / T(n);
  T pw = T(1);
  for (int k = 0; k < l; ++k) pw *= rho;
  return exp_fn(log_norm - r / T(n)) * pw * laguerre(n - l - 1, T(2 * l + 1), rho);
}

}  // namespace masav::hydrogen
