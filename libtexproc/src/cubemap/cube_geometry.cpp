// Cube map geometry: face directions, solid angles, the panorama mapping,
// layouts (crosses and strips), colour at the boundary, seam measurement.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "cubemap/cube_internal.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

const char* to_string(CubeLayout l) {
  switch (l) {
    case CubeLayout::equirect:
      return "equirect";
    case CubeLayout::cross_horizontal:
      return "hcross";
    case CubeLayout::cross_vertical:
      return "vcross";
    case CubeLayout::strip_horizontal:
      return "hstrip";
    case CubeLayout::strip_vertical:
      return "vstrip";
  }
  return "?";
}

CubeLayout parse_cube_layout(std::string_view name) {
  if (name == "equirect" || name == "latlong") return CubeLayout::equirect;
  if (name == "cross" || name == "hcross") return CubeLayout::cross_horizontal;
  if (name == "vcross") return CubeLayout::cross_vertical;
  if (name == "strip" || name == "hstrip") return CubeLayout::strip_horizontal;
  if (name == "vstrip") return CubeLayout::strip_vertical;
  throw Error(ErrorCode::bad_arguments, "unknown cube layout '" + std::string(name) +
                                            "' (valid: equirect, hcross, vcross, hstrip, vstrip; cross = hcross, "
                                            "strip = hstrip)");
}

CubeLayout detect_cube_layout(int w, int h) {
  if (w > 0 && h > 0) {
    if (w == 2 * h) return CubeLayout::equirect;
    if (w * 3 == h * 4 && w % 4 == 0) return CubeLayout::cross_horizontal;
    if (w * 4 == h * 3 && w % 3 == 0) return CubeLayout::cross_vertical;
    if (w == 6 * h) return CubeLayout::strip_horizontal;
    if (h == 6 * w) return CubeLayout::strip_vertical;
  }
  throw Error(ErrorCode::bad_arguments,
              std::to_string(w) + "x" + std::to_string(h) +
                  " is no cube map layout: a panorama is 2:1, a cross 4:3 or 3:4, a strip 6:1 or 1:6 (whole faces)");
}

CubeFlip parse_cube_flip(std::string_view name) {
  if (name == "none") return CubeFlip::none;
  if (name == "x") return CubeFlip::x;
  if (name == "y") return CubeFlip::y;
  if (name == "z") return CubeFlip::z;
  throw Error(ErrorCode::bad_arguments, "unknown flip axis '" + std::string(name) + "' (valid: none, x, y, z)");
}

void cube_direction(int face, double u, double v, double d[3]) {
  switch (face) {
    case 0:
      d[0] = 1, d[1] = -v, d[2] = -u;
      break;
    case 1:
      d[0] = -1, d[1] = -v, d[2] = u;
      break;
    case 2:
      d[0] = u, d[1] = 1, d[2] = v;
      break;
    case 3:
      d[0] = u, d[1] = -1, d[2] = -v;
      break;
    case 4:
      d[0] = u, d[1] = -v, d[2] = 1;
      break;
    default:
      d[0] = -u, d[1] = -v, d[2] = -1;
      break;
  }
}

int cube_face_uv(const double d[3], double& u, double& v) {
  const double ax = std::fabs(d[0]), ay = std::fabs(d[1]), az = std::fabs(d[2]);
  if (ax >= ay && ax >= az) {
    const double m = 1.0 / ax;
    v = -d[1] * m;
    if (d[0] >= 0) return u = -d[2] * m, 0;
    return u = d[2] * m, 1;
  }
  if (ay >= az) {
    const double m = 1.0 / ay;
    u = d[0] * m;
    if (d[1] >= 0) return v = d[2] * m, 2;
    return v = -d[2] * m, 3;
  }
  const double m = 1.0 / az;
  v = -d[1] * m;
  if (d[2] >= 0) return u = d[0] * m, 4;
  return u = -d[0] * m, 5;
}

namespace {
double corner_area(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }
}  // namespace

double cube_texel_solid_angle(int n, int i, int j) {
  const double x0 = 2.0 * i / n - 1.0, x1 = 2.0 * (i + 1) / n - 1.0;
  const double y0 = 2.0 * j / n - 1.0, y1 = 2.0 * (j + 1) / n - 1.0;
  return corner_area(x0, y0) - corner_area(x0, y1) - corner_area(x1, y0) + corner_area(x1, y1);
}

void direction_to_equirect(const double d[3], int width, int height, double& x, double& y) {
  const double phi = std::atan2(d[0], -d[2]);
  const double lambda = std::atan2(d[1], std::sqrt(d[0] * d[0] + d[2] * d[2]));
  x = (phi + std::numbers::pi) * (width / (2.0 * std::numbers::pi));
  y = (0.5 * std::numbers::pi - lambda) * (height / std::numbers::pi);
}

void equirect_direction(double x, double y, int width, int height, double d[3]) {
  const double phi = 2.0 * std::numbers::pi * x / width - std::numbers::pi;
  const double lambda = 0.5 * std::numbers::pi - std::numbers::pi * y / height;
  d[0] = std::sin(phi) * std::cos(lambda);
  d[1] = std::sin(lambda);
  d[2] = -std::cos(phi) * std::cos(lambda);
}

int default_cube_size(int panorama_width) {
  const double target = std::max(1.0, panorama_width / 4.0);
  int p = 1;
  while (p * 2 <= target) p *= 2;
  // nearest power of two (in log terms)
  return (target / p > std::sqrt(2.0)) ? p * 2 : p;
}

// ---- Colour at the boundary --------------------------------------------------

Image to_linear_rgba(const ConstImageView& image, const ColorSpace& cs) {
  Image out = Image::uninitialized(image.width, image.height, 4, PixelType::f32);
  const int c = image.channels;
  for_each_row_block(image.height, cube::kRowBlock, [&](int y0, int y1) {
    std::vector<float> row(std::size_t(image.width) * c);
    for (int y = y0; y < y1; ++y) {
      cs.decode_row(image.row<const std::uint8_t>(y), image.type, c, image.width, row.data());
      float* o = out.row<float>(y);
      for (int x = 0; x < image.width; ++x) {
        const float* p = row.data() + std::size_t(x) * c;
        float r, g, b, a = 1.0f;
        if (c <= 2) {
          r = g = b = p[0];
          if (c == 2) a = p[1];
        } else {
          r = p[0], g = p[1], b = p[2];
          if (c == 4) a = p[3];
        }
        o[4 * x + 0] = r * a;
        o[4 * x + 1] = g * a;
        o[4 * x + 2] = b * a;
        o[4 * x + 3] = a;
      }
    }
  });
  return out;
}

Image from_linear_rgba(const ConstImageView& rgba, const ColorSpace& cs, int channels, PixelType type) {
  if (rgba.channels != 4 || rgba.type != PixelType::f32 || (channels != 3 && channels != 4)) {
    throw Error(ErrorCode::bad_arguments, "from_linear_rgba needs RGBA f32 in and 3 or 4 channels out");
  }
  Image out = Image::uninitialized(rgba.width, rgba.height, channels, type);
  for_each_row_block(rgba.height, cube::kRowBlock, [&](int y0, int y1) {
    std::vector<float> row(std::size_t(rgba.width) * channels);
    for (int y = y0; y < y1; ++y) {
      const float* p = rgba.row<const float>(y);
      for (int x = 0; x < rgba.width; ++x) {
        const float a = p[4 * x + 3];
        const float inv = a > 0.0f ? 1.0f / a : 0.0f;
        float* o = row.data() + std::size_t(x) * channels;
        for (int k = 0; k < 3; ++k) o[k] = p[4 * x + k] * inv;
        if (channels == 4) o[3] = a;
      }
      cs.encode_row(row.data(), channels, rgba.width, out.row<std::uint8_t>(y), type);
    }
  });
  return out;
}

// ---- Levels, faces and layouts -------------------------------------------------

namespace cube {

CubeLevel make_level(int n) {
  CubeLevel l;
  l.size = n;
  for (Image& f : l.faces) f = Image::uninitialized(n, n, 4, PixelType::f32);
  return l;
}

TexelSet texel_set(const CubeLevel& level) {
  const int n = level.size;
  TexelSet s;
  const std::size_t count = std::size_t(6) * n * n;
  for (auto* v : {&s.x, &s.y, &s.z, &s.w, &s.r, &s.g, &s.b}) v->resize(count);
  std::vector<double> solid(std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) solid[std::size_t(j) * n + i] = cube_texel_solid_angle(n, i, j);
  std::size_t k = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j) {
      const float* row = level.faces[f].row<float>(j);
      for (int i = 0; i < n; ++i, ++k) {
        double d[3];
        texel_direction(f, n, i, j, d);
        s.x[k] = float(d[0]);
        s.y[k] = float(d[1]);
        s.z[k] = float(d[2]);
        s.w[k] = float(solid[std::size_t(j) * n + i]);
        s.r[k] = row[4 * i];
        s.g[k] = row[4 * i + 1];
        s.b[k] = row[4 * i + 2];
      }
    }
  return s;
}

}  // namespace cube

namespace {

void check_rgba_f32(const ConstImageView& v, const char* what) {
  if (v.channels != 4 || v.type != PixelType::f32 || v.width < 1 || v.height < 1) {
    throw Error(ErrorCode::bad_arguments, std::string(what) + " needs a linear RGBA f32 image (to_linear_rgba)");
  }
}

// Cell (column, row) of each face in a layout, and whether it is turned 180 degrees.
struct Cell {
  int col, row;
  bool turned;
};
Cell layout_cell(CubeLayout l, int face) {
  static constexpr int kCross[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
  switch (l) {
    case CubeLayout::cross_horizontal:
      return {kCross[face][0], kCross[face][1], false};
    case CubeLayout::cross_vertical:
      if (face == 5) return {1, 3, true};
      return {kCross[face][0], kCross[face][1], false};
    case CubeLayout::strip_horizontal:
      return {face, 0, false};
    case CubeLayout::strip_vertical:
      return {0, face, false};
    case CubeLayout::equirect:
      break;
  }
  return {0, 0, false};
}
void layout_grid(CubeLayout l, int& cols, int& rows) {
  switch (l) {
    case CubeLayout::cross_horizontal:
      cols = 4, rows = 3;
      return;
    case CubeLayout::cross_vertical:
      cols = 3, rows = 4;
      return;
    case CubeLayout::strip_horizontal:
      cols = 6, rows = 1;
      return;
    case CubeLayout::strip_vertical:
      cols = 1, rows = 6;
      return;
    case CubeLayout::equirect:
      break;
  }
  cols = rows = 0;
}

}  // namespace

Cubemap cubemap_from_faces(const std::array<ConstImageView, 6>& faces) {
  static const char* kNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (int f = 0; f < 6; ++f) {
    check_rgba_f32(faces[f], "cubemap_from_faces");
    if (faces[f].width != faces[f].height || faces[f].width != faces[0].width) {
      throw Error(ErrorCode::bad_arguments,
                  std::string("face ") + kNames[f] + " is " + std::to_string(faces[f].width) + "x" +
                      std::to_string(faces[f].height) + ": every face must be square and of one size (+X is " +
                      std::to_string(faces[0].width) + "x" + std::to_string(faces[0].height) + ")");
    }
  }
  const int n = faces[0].width;
  Cubemap c;
  c.levels.push_back(cube::make_level(n));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y) std::memcpy(c.levels[0].faces[f].row<float>(y), faces[f].row<const float>(y), n * 16);
  return c;
}

Cubemap cubemap_from_images(const std::vector<Image>& faces) {
  if (faces.size() != 6) {
    throw Error(ErrorCode::bad_arguments,
                "a cube map has 6 faces; this texture has " + std::to_string(faces.size()) + " images");
  }
  std::array<ConstImageView, 6> v;
  for (int f = 0; f < 6; ++f) v[f] = faces[f].view();
  return cubemap_from_faces(v);
}

Cubemap cubemap_from_layout(const ConstImageView& image, CubeLayout layout) {
  check_rgba_f32(image, "cubemap_from_layout");
  int cols, rows;
  layout_grid(layout, cols, rows);
  if (cols == 0) throw Error(ErrorCode::bad_arguments, "cubemap_from_layout: an equirect panorama has no faces");
  const int n = image.width / cols;
  if (n < 1 || image.width != n * cols || image.height != n * rows) {
    throw Error(ErrorCode::bad_arguments, std::to_string(image.width) + "x" + std::to_string(image.height) +
                                              " does not fit a " + to_string(layout) + " layout (" +
                                              std::to_string(cols) + " x " + std::to_string(rows) + " square faces)");
  }
  Cubemap c;
  c.levels.push_back(cube::make_level(n));
  for (int f = 0; f < 6; ++f) {
    const Cell cell = layout_cell(layout, f);
    for (int y = 0; y < n; ++y) {
      float* dst = c.levels[0].faces[f].row<float>(y);
      const int sy = cell.turned ? n - 1 - y : y;
      const float* src = image.row<const float>(cell.row * n + sy) + std::size_t(cell.col) * n * 4;
      if (!cell.turned) {
        std::memcpy(dst, src, std::size_t(n) * 16);
      } else {
        for (int x = 0; x < n; ++x) std::memcpy(dst + 4 * x, src + 4 * (n - 1 - x), 16);
      }
    }
  }
  return c;
}

Image cubemap_to_layout(const Cubemap& cube, CubeLayout layout, int level) {
  int cols, rows;
  layout_grid(layout, cols, rows);
  if (cols == 0) throw Error(ErrorCode::bad_arguments, "cubemap_to_layout: use cubemap_to_equirect for a panorama");
  const CubeLevel& l = cube.levels.at(level);
  const int n = l.size;
  Image out(n * cols, n * rows, 4, PixelType::f32);
  for (int f = 0; f < 6; ++f) {
    const Cell cell = layout_cell(layout, f);
    for (int y = 0; y < n; ++y) {
      const float* src = l.faces[f].row<float>(cell.turned ? n - 1 - y : y);
      float* dst = out.row<float>(cell.row * n + y) + std::size_t(cell.col) * n * 4;
      if (!cell.turned) {
        std::memcpy(dst, src, std::size_t(n) * 16);
      } else {
        for (int x = 0; x < n; ++x) std::memcpy(dst + 4 * x, src + 4 * (n - 1 - x), 16);
      }
    }
  }
  return out;
}

namespace {
// The texel of an n x n face that direction d falls in.
void texel_of(const double d[3], int n, int& face, int& i, int& j) {
  double u, v;
  face = cube_face_uv(d, u, v);
  i = std::clamp(int(std::floor((u + 1.0) * 0.5 * n)), 0, n - 1);
  j = std::clamp(int(std::floor((v + 1.0) * 0.5 * n)), 0, n - 1);
}
}  // namespace

Cubemap flip_cubemap(const Cubemap& cube, CubeFlip flip) {
  if (flip == CubeFlip::none) return cube;
  const int axis = flip == CubeFlip::x ? 0 : flip == CubeFlip::y ? 1 : 2;
  Cubemap out;
  for (const CubeLevel& l : cube.levels) {
    const int n = l.size;
    CubeLevel o = cube::make_level(n);
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          double d[3];
          cube::texel_direction(f, n, i, j, d);
          d[axis] = -d[axis];
          int sf, si, sj;
          texel_of(d, n, sf, si, sj);
          std::memcpy(o.faces[f].row<float>(j) + 4 * i, l.faces[sf].row<float>(sj) + 4 * si, 16);
        }
    out.levels.push_back(std::move(o));
  }
  return out;
}

SeamStats measure_seams(const CubeLevel& level) {
  const int n = level.size;
  auto step = [](const float* a, const float* b) {
    return (std::fabs(a[0] - b[0]) + std::fabs(a[1] - b[1]) + std::fabs(a[2] - b[2])) / 3.0;
  };
  double edge = 0, inner = 0, near = 0;
  std::size_t edges = 0, inners = 0, nears = 0;
  for (int f = 0; f < 6; ++f) {
    const Image& face = level.faces[f];
    auto at = [&](int i, int j) { return face.row<float>(j) + 4 * i; };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (i + 1 < n) {
          inner += step(at(i, j), at(i + 1, j));
          ++inners;
        }
        if (j + 1 < n) {
          inner += step(at(i, j), at(i, j + 1));
          ++inners;
        }
      }
    // Along each edge: the texel across it (one texel outward on the
    // extended plane) and the texel inward of the edge texel.
    for (int k = 0; k < n; ++k) {
      const int pos[4][6] = {
          {0, k, -1, k, 1, k}, {n - 1, k, n, k, n - 2, k}, {k, 0, k, -1, k, 1}, {k, n - 1, k, n, k, n - 2}};
      for (const auto& p : pos) {
        if (n >= 2) {
          near += step(at(p[0], p[1]), at(p[4], p[5]));
          ++nears;
        }
        double d[3];
        cube_direction(f, 2.0 * (p[2] + 0.5) / n - 1.0, 2.0 * (p[3] + 0.5) / n - 1.0, d);
        int of, oi, oj;
        texel_of(d, n, of, oi, oj);
        if (of <= f) continue;  // each pair once
        edge += step(at(p[0], p[1]), level.faces[of].row<float>(oj) + 4 * oi);
        ++edges;
      }
    }
  }
  return {edges ? edge / edges : 0.0, inners ? inner / inners : 0.0, nears ? near / nears : 0.0};
}

}  // namespace texproc
