// The scalar reference of bc1_cluster.h (namespace ref): what bc1_cluster_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "bc/bc1_cluster.h"

#include <algorithm>
#include <limits>

namespace texproc::ref {

void cluster_splits(const double pre[17][3], double total_sq, int n, int i, int j, ClusterRow& out, int k0) {
  const double s0 = i, s1 = j - i;
  for (int k = std::max(j, k0); k <= n; ++k) {
    const int at = k - j;
    const double s2 = k - j, s3 = n - k;
    const double aa = (s0 + (4.0 / 9.0) * s1) + (1.0 / 9.0) * s2;
    const double bb = (s3 + (1.0 / 9.0) * s1) + (4.0 / 9.0) * s2;
    const double ab = (2.0 / 9.0) * (s1 + s2);
    const double det = aa * bb - ab * ab;
    if (det < 1e-9) {
      out.err[at] = std::numeric_limits<double>::infinity();
      continue;
    }
    const double inv = 1.0 / det;
    double err = total_sq;
    for (int c = 0; c < 3; ++c) {
      const double x1 = pre[j][c] - pre[i][c], x2 = pre[k][c] - pre[j][c];
      const double xa = (pre[i][c] + (2.0 / 3.0) * x1) + (1.0 / 3.0) * x2;
      const double xb = ((pre[n][c] - pre[k][c]) + (1.0 / 3.0) * x1) + (2.0 / 3.0) * x2;
      const double a = std::min(std::max((xa * bb - xb * ab) * inv, 0.0), 255.0);
      const double b = std::min(std::max((xb * aa - xa * ab) * inv, 0.0), 255.0);
      out.a[at][c] = a;
      out.b[at][c] = b;
      const double fit = -2.0 * (a * xa + b * xb);
      const double quad = ((a * a) * aa + ((2.0 * a) * b) * ab) + (b * b) * bb;
      err = err + (fit + quad);
    }
    out.err[at] = err;
  }
}

}  // namespace texproc::ref
