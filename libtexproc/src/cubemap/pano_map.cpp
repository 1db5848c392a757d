// Scalar reference of the face-row mapping (pano_map.h).
#include "cubemap/pano_map.h"

#include <algorithm>
#include <cmath>

namespace texproc::cube {

namespace {
constexpr float kPi = 3.14159265358979f;
}  // namespace

float atan2_poly(float y, float x) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float mx = std::max(std::max(ax, ay), 1e-30f), mn = std::min(ax, ay);
  float t = mn / mx, base = 0.0f;
  if (t > 0.414213562f) {
    t = (t - 1.0f) / (t + 1.0f);
    base = kPi / 4;
  }
  const float z = t * t;
  const float p =
      ((((0.0805374449538f * z - 0.138776856032f) * z + 0.199777106478f) * z - 0.333329491539f) * z) * t + t;
  float a = base + p;
  if (ay > ax) a = kPi / 2 - a;
  if (x < 0.0f) a = kPi - a;
  if (y < 0.0f) a = -a;
  return a;
}

namespace ref {

void map_face_row(const float axes[9], int n, int j, int width, int height, const FaceRowMap& out) {
  const float step = 2.0f / float(n), offset = 1.0f / float(n) - 1.0f;
  const float v = float(j) * step + offset;
  const float sx = float(width) / (2 * kPi), sy = float(height) / kPi;
  const float* c = axes;
  const float* eu = axes + 3;
  const float* ev = axes + 6;
  for (int i = 0; i < n; ++i) {
    const float u = float(i) * step + offset;
    float d[3];
    for (int k = 0; k < 3; ++k) d[k] = (c[k] + u * eu[k]) + v * ev[k];
    const float rho2 = std::max(d[0] * d[0] + d[2] * d[2], 1e-30f);
    const float rho = std::sqrt(rho2), r2 = rho2 + d[1] * d[1];
    const float phi = atan2_poly(d[0], -d[2]), lambda = atan2_poly(d[1], rho);
    out.px[i] = (phi + kPi) * sx;
    out.py[i] = (kPi / 2 - lambda) * sy;
    out.cosl[i] = rho / std::sqrt(r2);
    const float* e[2] = {eu, ev};
    float* jx[2] = {out.ax, out.bx};
    float* jy[2] = {out.ay, out.by};
    for (int s = 0; s < 2; ++s) {
      const float dphi = (e[s][2] * d[0] - e[s][0] * d[2]) / rho2;
      const float drho = (d[0] * e[s][0] + d[2] * e[s][2]) / rho;
      const float dlam = (rho * e[s][1] - d[1] * drho) / r2;
      jx[s][i] = dphi * sx * step;
      jy[s][i] = -(dlam * sy * step);
    }
  }
}

}  // namespace ref
}  // namespace texproc::cube
