// The inner loop of BC1's cluster fit, SIMD and scalar twins: for the texels
// ordered along an axis (prefix sums `pre` of their colours, n of them), the
// splits into four consecutive clusters [0, i) [i, j) [j, k) [k, n) for
// fixed i and j and every k in [j, n]: each split's least-squares endpoints
// a, b (clamped to [0, 255]) and its squared error. A split whose normal
// equations are singular gets error +infinity. Both twins evaluate the same
// expressions in the same order (no FMA): identical results.
#pragma once

namespace texproc {

struct ClusterRow {
  double err[17];
  double a[17][3], b[17][3];  // by k - j
};

void cluster_splits(const double pre[17][3], double total_sq, int n, int i, int j, ClusterRow& out);

namespace ref {
// The same for k in [k0, n] only (the SIMD twin finishes its row with it).
void cluster_splits(const double pre[17][3], double total_sq, int n, int i, int j, ClusterRow& out, int k0 = -1);
}  // namespace ref

}  // namespace texproc
