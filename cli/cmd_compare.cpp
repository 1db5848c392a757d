// texproc compare: how far two images or textures are apart (PSNR, RMSE,
// max error, SSIM), and an exit code for scripts: 7 when they differ beyond
// the given limits.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include "batch.h"
#include "commands.h"
#include "common.h"
#include "report.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/metrics.h"
#include "texproc/runtime.h"

namespace texproc::cli {
namespace {

struct CompareArgs {
  std::string a, b;
  int level = 0;
  double min_psnr = -1, max_error = -1, min_ssim = -1, max_log_rmse = -1;
  bool ssim = false, json = false;
};

// An image file, or one level of a texture, decoded band by band as the
// comparison reaches it (SNORM to [0, 1]).
struct Loaded {
  Image image;
  Texture texture;
  bool is_texture = false;
  std::uint32_t level = 0;
  ImageView shape;  // width, height, channels and type of what is compared
};

Loaded load(const std::string& path, int level) {
  Loaded l;
  if (is_texture_container(path)) {
    l.texture = read_texture(path, cli_read_options().limits);
    l.is_texture = true;
    if (level < 0 || std::uint32_t(level) >= l.texture.levels) {
      throw Error(ErrorCode::bad_arguments, path + ": --level " + std::to_string(level) + " (valid: 0 to " +
                                                std::to_string(l.texture.levels - 1) + ")");
    }
    l.level = std::uint32_t(level);
    l.shape.width = int(l.texture.level_width(l.level));
    l.shape.height = int(l.texture.level_height(l.level));
    l.shape.channels = format_info(l.texture.format).channels;
    l.shape.type = PixelType::f32;
    return l;
  }
  if (level != 0) throw Error(ErrorCode::bad_arguments, path + ": --level applies to textures (.dds, .ktx2, .ktx)");
  l.image = read_image(path, nullptr, cli_read_options());
  l.shape = l.image.view();
  return l;
}

// The first `n` channels of what was loaded, as rows made on demand: a
// texture's decoded, an image's as they are (or as floats when only some
// of its channels are compared).
ImageRows rows_of(const Loaded& l, int n) {
  if (!l.is_texture && l.shape.channels == n) return ImageRows{l.shape, {}};
  ImageRows r;
  r.shape = l.shape;
  r.shape.data = nullptr;
  r.shape.channels = n;
  r.shape.type = PixelType::f32;
  r.rows = [&l, n](int y0, int y1, void* dst, std::size_t stride) {
    const int w = l.shape.width, C = l.shape.channels;
    std::vector<float> decoded;
    if (l.is_texture) {
      decoded.resize(std::size_t(w) * C * std::size_t(y1 - y0));
      decode_texture_rows(l.texture, l.level, 0, 0, PixelType::f32, y0, y1, decoded.data(), std::size_t(w) * C * 4);
    }
    const bool snorm = l.is_texture && format_info(l.texture.format).snorm;
    for (int y = y0; y < y1; ++y) {
      float* out = reinterpret_cast<float*>(static_cast<std::uint8_t*>(dst) + std::size_t(y - y0) * stride);
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < n; ++c) {
          float v = l.is_texture ? decoded[(std::size_t(y - y0) * w + x) * C + c] : l.image.get(x, y, c);
          out[x * n + c] = snorm ? (v + 1.0f) * 0.5f : v;
        }
    }
  };
  return r;
}

// All of it at once (SSIM's planes need every row).
Image whole(const ImageRows& r) {
  Image img = Image::uninitialized(r.shape.width, r.shape.height, r.shape.channels, r.shape.type);
  if (!r.rows) {
    for (int y = 0; y < img.height(); ++y) std::memcpy(img.row<void>(y), r.shape.row<const void>(y), img.row_stride());
  } else {
    r.rows(0, img.height(), img.data(), img.row_stride());
  }
  return img;
}

Json::Value finite(double v) { return std::isfinite(v) ? Json::Value(v) : Json::Value(); }

// A figure as a number, or as the word for what it is: nan, inf, -inf.
std::string number(double v, const char* format = "%g") {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char b[32];
  std::snprintf(b, sizeof b, format, v);
  return b;
}
std::string db(double v) { return number(v, "%.2f"); }

// Limits compare so that a NaN figure fails them.
bool below(double value, double limit) { return !(value >= limit); }
bool above(double value, double limit) { return !(value <= limit); }

int run_compare(const CompareArgs& a) {
  ThreadLimit threads(run_options().threads);
  const Loaded la = load(a.a, a.level), lb = load(a.b, a.level);
  const ConstImageView& ia = la.shape;
  const ConstImageView& ib = lb.shape;
  if (ia.width != ib.width || ia.height != ib.height) {
    throw Error(ErrorCode::bad_arguments, a.a + " is " + std::to_string(ia.width) + "x" + std::to_string(ia.height) +
                                              ", " + a.b + " is " + std::to_string(ib.width) + "x" +
                                              std::to_string(ib.height) +
                                              ": images of different sizes cannot be compared");
  }
  // The log2 RMSE is computed for float images only: a limit on two 8/16-bit
  // images would pass whatever they hold.
  if (a.max_log_rmse >= 0 && ia.type != PixelType::f32 && ib.type != PixelType::f32) {
    throw Error(ErrorCode::bad_arguments, "--max-log-rmse: " + a.a + " and " + a.b +
                                              " hold 8/16-bit values, not floats; the log2 RMSE is for HDR images "
                                              "(use --min-psnr)");
  }
  // A texture format may store fewer channels than the image it came from
  // (BC1: RGB of an RGBA image): compare the channels both have.
  const int n = std::min(ia.channels, ib.channels);
  const ImageRows ra = rows_of(la, n), rb = rows_of(lb, n);
  const ImageDifference d = compare_image_rows(ra, rb, n);
  const bool want_ssim = a.ssim || a.min_ssim >= 0;
  const std::vector<double> ssim =
      want_ssim ? ssim_per_channel(whole(ra).view(), whole(rb).view()) : std::vector<double>{};
  double ssim_mean = 0;
  for (double s : ssim) ssim_mean += s / double(ssim.size());

  std::vector<std::string> failed;
  const bool limits = a.min_psnr >= 0 || a.max_error >= 0 || a.min_ssim >= 0 || a.max_log_rmse >= 0;
  if (!limits && d.differing_texels > 0) failed.push_back("texels differ");
  // NaN and infinities are differences whatever the limits: the figures
  // describe the finite texels only.
  if (d.nonfinite_texels > 0) failed.push_back(std::to_string(d.nonfinite_texels) + " texels hold NaN or infinity");
  if (a.min_psnr >= 0 && below(d.psnr(), a.min_psnr))
    failed.push_back("PSNR " + db(d.psnr()) + " dB < " + db(a.min_psnr));
  if (a.max_error >= 0 && above(d.max_abs, a.max_error)) {
    failed.push_back("max error " + number(d.max_abs) + " > " + number(a.max_error));
  }
  if (a.max_log_rmse >= 0 && above(d.log_rmse_rgb(), a.max_log_rmse)) {
    failed.push_back("log2 RMSE " + number(d.log_rmse_rgb()) + " > " + number(a.max_log_rmse));
  }
  if (a.min_ssim >= 0 && below(ssim_mean, a.min_ssim)) {
    failed.push_back("SSIM " + number(ssim_mean) + " < " + number(a.min_ssim));
  }
  const int rc = failed.empty() ? 0 : int(ErrorCode::difference_found);

  const char* names = n >= 3 ? "RGBA" : n == 2 ? "RG" : "R";
  if (a.json) {
    Json::Value j(Json::objectValue);
    j["a"] = a.a;
    j["b"] = a.b;
    j["width"] = d.width;
    j["height"] = d.height;
    j["channels"] = n;
    j["psnr"] = finite(d.psnr());
    if (n >= 3) j["psnr_rgb"] = finite(d.psnr_rgb());
    j["rmse"] = finite(std::sqrt(d.mse));
    j["max_error"] = finite(d.max_abs);
    j["log_rmse_rgb"] = finite(d.log_rmse_rgb());
    j["hdr"] = d.hdr;
    j["differing_texels"] = Json::UInt64(d.differing_texels);
    j["nonfinite_texels"] = Json::UInt64(d.nonfinite_texels);
    Json::Value per(Json::arrayValue);
    for (int c = 0; c < n; ++c) {
      Json::Value ch(Json::objectValue);
      ch["name"] = std::string(1, names[c]);
      ch["psnr"] = finite(d.psnr_channel(c));
      ch["rmse"] = finite(std::sqrt(d.channel[std::size_t(c)].mse));
      ch["mean_error"] = finite(d.channel[std::size_t(c)].mean_abs);
      ch["max_error"] = finite(d.channel[std::size_t(c)].max_abs);
      if (want_ssim) ch["ssim"] = finite(ssim[std::size_t(c)]);
      per.append(ch);
    }
    j["channel"] = per;
    if (want_ssim) j["ssim"] = finite(ssim_mean);
    j["identical"] = d.differing_texels == 0;
    j["within_limits"] = failed.empty();
    std::cout << to_json(j) << "\n";
  } else if (!run_options().quiet) {
    std::ostringstream s;
    s << a.a << " vs " << a.b << ": " << d.width << "x" << d.height << "x" << n << ", PSNR " << db(d.psnr()) << " dB";
    if (n >= 3) s << " (RGB " << db(d.psnr_rgb()) << " dB)";
    s << " [";
    for (int c = 0; c < n; ++c) s << (c ? " " : "") << names[c] << " " << db(d.psnr_channel(c));
    s << "], RMSE " << number(std::sqrt(d.mse)) << ", max error " << number(d.max_abs);
    if (std::isfinite(d.max_abs)) s << " (" << std::lround(d.max_abs * 255) << "/255)";
    if (d.hdr) s << ", log2 RMSE " << number(d.log_rmse_rgb()) << " (HDR)";
    if (want_ssim) s << ", SSIM " << number(ssim_mean);
    char pct[32];
    std::snprintf(pct, sizeof pct, "%.2f", 100.0 * double(d.differing_texels) / (double(d.width) * d.height));
    s << ", " << d.differing_texels << " texels differ (" << pct << "%)";
    if (d.nonfinite_texels > 0) s << ", " << d.nonfinite_texels << " of them NaN or infinite";
    std::cout << s.str() << "\n";
  }
  if (!failed.empty()) print_note("texproc compare: " + a.a + " and " + a.b + " differ: " + join(failed));
  return rc;
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "Compare two images or textures: PSNR, RMSE, max error, SSIM.");
  cmd->footer(
      "Values are compared on a [0, 1] scale (8-bit codes / 255, 16-bit / 65535, floats as stored; textures\n"
      "decoded, SNORM mapped to [0, 1]). With no limit given, exit 7 when any texel differs; with limits,\n"
      "exit 7 when one is not met. When the channel counts differ, the channels both have are compared.\n"
      "HDR (float images with values outside [0, 1]): PSNR on that scale says little, so the line adds the\n"
      "log2 RMSE over RGB, the RMSE of sign(v) log2(1 + |v|): about stops for bright values, linear near 0.");
  cmd->add_option("a", args->a, "First image or texture")->required();
  cmd->add_option("b", args->b, "Second image or texture")->required();
  cmd->add_option("--level", args->level, "Mip level of textures to compare (default 0)")->check(in_range(0, 31));
  cmd->add_option("--min-psnr", args->min_psnr, "Exit 7 when the PSNR (all channels) is below this, in dB")
      ->check(in_range(0, 1000));
  cmd->add_option("--max-error", args->max_error,
                  "Exit 7 when any value differs by more than this (0..1; 1/255 = 0.0039)")
      ->check(in_range(0, 3.4e38));
  cmd->add_option("--max-log-rmse", args->max_log_rmse,
                  "Exit 7 when the log2 RMSE over RGB (the HDR metric, float images) is above this")
      ->check(in_range(0, 1000));
  cmd->add_option("--min-ssim", args->min_ssim, "Exit 7 when the mean SSIM is below this (0..1)")
      ->check(in_range(-1, 1));
  cmd->add_flag("--ssim", args->ssim, "Also compute SSIM (11x11 Gaussian window)");
  cmd->add_option("--threads", run_options().threads, "Worker threads (default 0: all cores)")
      ->check(in_range(0, 4096));
  cmd->add_flag("-q,--quiet", run_options().quiet, "Print nothing; the exit code tells");
  cmd->add_flag("--json", args->json, "Print the figures as one JSON object");
  set_runner(*cmd, [args] { return run_compare(*args); });
}

}  // namespace texproc::cli
