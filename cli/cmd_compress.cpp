// texproc compress: block compression (BC1-BC5, BC7, ETC1, ETC2, EAC, ASTC) into
// DDS, KTX2, KTX1, PKM or .astc, optionally with a mip chain.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <iostream>
#include <filesystem>
#include <optional>

#include "commands.h"
#include "batch.h"
#include "common.h"
#include "texproc/block_decode.h"
#include "texproc/metrics.h"
#include "texproc/block_encode.h"
#include "texproc/color.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"
#include "texproc/transparent_color.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct CompressArgs {
  SizeArgs size;
  ChannelArgs channels;
  BatchInputs io;
  ChainArgs chain;
  std::string format, quality = "normal", wrap = "clamp", dds_header = "auto";
  int zstd = 0;
  float astc_effort = -1.0f;  // astc-encoder's numeric quality, in place of --quality's preset
  std::string transparent_color = "keep";
  bool mips = false, normal_map = false, linear = false, srgb = false, report = false, bc1_black = false;
  int mips_flag = 0;             // --mips 1, --no-mips -1, neither 0 (the role's default)
  std::string role, target;      // --role, --target: defaults for what the options leave out
  bool web_zstd = false;         // --target web: Zstandard level 19 for KTX2 outputs
  bool clip = false;             // float input outside [0, 1] to an LDR format: meant, no warning
  float alpha_coverage = -1.0f;  // with --mips: the alpha reference whose coverage each level keeps
  bool no_premultiply = false;   // with --mips: alpha is data, not coverage
  // From the options, once (validate):
  Quality q = Quality::normal;
  DdsHeader header = DdsHeader::automatic;
  TransparentColor transparent = TransparentColor::keep;
  MipOptions mip;  // with --mips; the colour space is set per file
};

// What --role chooses where the options do not: the format for each
// --target, how the input is read, and the chain.
struct RolePreset {
  const char* role;
  const char* desktop;
  const char* mobile;
  const char* web;
  bool linear, normal_map, mips;
  float alpha_coverage;  // < 0: none
};
constexpr RolePreset kRoles[] = {
    {"color", "bc7", "astc-6x6", "bc7", false, false, true, -1.0f},
    {"color-alpha", "bc7", "astc-6x6", "bc7", false, false, true, -1.0f},
    {"cutout", "bc7", "astc-6x6", "bc7", false, false, true, 0.5f},
    {"normal", "bc5", "eac-rg11", "bc5", true, true, true, -1.0f},
    {"mask", "bc7", "astc-6x6", "bc7", true, false, true, -1.0f},
    {"height", "bc4", "eac-r11", "bc4", true, false, true, -1.0f},
    {"hdr", "bc6h", "astc-6x6-hdr", "bc6h", false, false, true, -1.0f},
    {"ui", "bc7", "astc-4x4", "bc7", false, false, false, -1.0f},
};

// Fills in what --role and --target choose and the options left out; sets
// a.mips from --mips/--no-mips or the role.
void apply_role(CompressArgs& a) {
  const RolePreset* preset = nullptr;
  if (!a.role.empty()) {
    std::string names;
    for (const RolePreset& p : kRoles) {
      if (a.role == p.role) preset = &p;
      names += std::string(names.empty() ? "" : ", ") + p.role;
    }
    if (!preset) throw Error(ErrorCode::bad_arguments, "--role " + a.role + ": valid: " + names);
  }
  const std::string target = a.target.empty() ? "desktop" : a.target;
  if (target != "desktop" && target != "mobile" && target != "web")
    throw Error(ErrorCode::bad_arguments, "--target " + a.target + ": valid: desktop, mobile, web");
  if (!a.target.empty() && !preset)
    throw Error(ErrorCode::bad_arguments, "--target " + a.target + " picks a format for a --role: add --role");
  a.mips = a.mips_flag > 0 || (a.mips_flag == 0 && preset && preset->mips);
  if (!preset) {
    if (a.format.empty())
      throw Error(ErrorCode::bad_arguments, "--format is required (or --role ROLE [--target desktop|mobile|web])");
    return;
  }
  if (a.format.empty())
    a.format = target == "mobile" ? preset->mobile : target == "web" ? preset->web : preset->desktop;
  if (preset->linear && !a.srgb) a.linear = true;
  if (preset->normal_map) a.normal_map = true;
  if (preset->alpha_coverage > 0.0f && a.alpha_coverage < 0.0f && a.mips) a.alpha_coverage = preset->alpha_coverage;
  a.web_zstd = target == "web" && a.zstd == 0;
}

// An image that looks like a tangent-space normal map (nearly every texel a
// unit vector pointing out of the surface) about to be stored as sRGB
// colour: its vectors would be bent by the transfer function.
void warn_if_normal_map_as_srgb(const std::string& input, const Image& img, bool srgb,
                                std::vector<std::string>& warnings) {
  if (!srgb || img.channels() < 3 || img.type() == PixelType::f32) return;
  const int step = std::max(1, int(std::sqrt(double(img.width()) * img.height() / 4096.0)));
  std::size_t texels = 0, unit = 0;
  for (int y = 0; y < img.height(); y += step)
    for (int x = 0; x < img.width(); x += step) {
      const double nx = img.get(x, y, 0) * 2 - 1, ny = img.get(x, y, 1) * 2 - 1, nz = img.get(x, y, 2) * 2 - 1;
      ++texels;
      if (nz > 0.2 && std::abs(std::sqrt(nx * nx + ny * ny + nz * nz) - 1.0) < 0.15) ++unit;
    }
  if (texels >= 16 && unit >= texels * 9 / 10) {
    warnings.push_back(input +
                       ": looks like a tangent-space normal map (unit vectors, blue up) but is stored as sRGB colour; "
                       "--normal-map (or --role normal) stores it as data, --srgb says the colour is meant");
  }
}

// Alpha below opaque that a format without alpha (BC1, ETC1, ETC2 RGB, BC6H) drops.
void warn_if_alpha_dropped(const std::string& input, const Image& img, TexelFormat format,
                           std::vector<std::string>& warnings) {
  const int n = img.channels();
  if (format_info(format).channels != 3 || (n != 2 && n != 4)) return;
  std::size_t below = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (img.get(x, y, n - 1) < 1.0f) ++below;
  if (below == 0) return;
  warnings.push_back(input + ": alpha is below 1 in " + std::to_string(below) + " texel(s), and " +
                     format_info(format).name +
                     " has no alpha: it is dropped (bc1a, bc7, etc2a, etc2a1 or astc keep it)");
}

// A DXT name asks for what DX9-era tools read; sRGB colour in DDS needs the
// DX10 header, which some of them (NVTT 2's nvdecompress) cannot read.
void warn_if_dx10_for_dxt(const CompressArgs& a, TexelFormat format, const std::string& output,
                          std::vector<std::string>& warnings) {
  std::string f = a.format;
  for (char& c : f) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool dxt = f == "dxt1" || f == "dxt1a" || f == "dxt3" || f == "dxt5";
  if (!dxt || !format_info(format).srgb || a.header == DdsHeader::dx9) return;
  if (fs::path(output).extension() != ".dds") return;
  warnings.push_back(output + ": --format " + a.format + " on sRGB colour writes " + format_info(format).name +
                     ", which needs a DX10 header that DX9-era readers (NVTT 2) cannot read; --linear writes a "
                     "legacy DXT" +
                     f.substr(3, 1) + " header (UNORM)");
}

void validate(CompressArgs& a) {
  apply_role(a);
  validate_size_options(a.size);
  validate_channel_options(a.channels);
  if (a.linear && a.srgb) throw Error(ErrorCode::bad_arguments, "--srgb and --linear contradict each other");
  a.q = parse_quality(a.quality);
  a.header = parse_dds_header(a.dds_header);
  a.transparent = parse_transparent_color(a.transparent_color);
  block_format_for(a.format, false);  // a known format, or an error now
  if (const auto t = exact_block_format(a.format); t && !format_info(*t).is_float) {
    const bool named_srgb = format_info(*t).srgb;
    if (a.srgb && !named_srgb) throw Error(ErrorCode::bad_arguments, "--srgb contradicts --format " + a.format);
    if (a.linear && named_srgb) throw Error(ErrorCode::bad_arguments, "--linear contradicts --format " + a.format);
  }
  if (a.srgb && format_info(block_format_for(a.format, false)).is_float) {
    throw Error(ErrorCode::bad_arguments, "--srgb: --format " + a.format + " is HDR (linear floats); drop --srgb");
  }
  if (a.srgb && !format_info(block_format_for(a.format, true)).srgb) {
    throw Error(ErrorCode::bad_arguments,
                "--srgb: --format " + a.format + " has no sRGB variant (it holds data); drop --srgb");
  }
  // Options of the mip chain mean nothing without one (--levels also keeps
  // an input texture's first levels: checked per file).
  if (!a.mips) {
    const ChainArgs defaults;
    const char* given = a.chain.min_size != defaults.min_size ? "--min-size"
                        : a.chain.filter != defaults.filter   ? "--filter"
                        : a.chain.sigma != defaults.sigma     ? "--sigma"
                                                              : nullptr;
    if (given) throw Error(ErrorCode::bad_arguments, std::string(given) + " shapes the mip chain: add --mips");
  }
  const TexelFormat linear_format = block_format_for(a.format, false);
  if (a.astc_effort >= 0.0f && !is_astc(linear_format))
    throw Error(ErrorCode::bad_arguments, "--astc-effort applies to the ASTC formats, not '" + a.format + "'");
  if (a.astc_effort >= 0.0f && a.astc_effort > 100.0f)
    throw Error(ErrorCode::bad_arguments, "--astc-effort " + std::to_string(a.astc_effort) + " is not in [0, 100]");
  if (a.normal_map && format_info(linear_format).is_float)
    throw Error(ErrorCode::bad_arguments,
                "--normal-map: a normal map is LDR data; use astc-WxH, not '" + a.format + "'");
  if (a.bc1_black && linear_format != TexelFormat::bc1_rgb_unorm)
    throw Error(ErrorCode::bad_arguments,
                "--bc1-black applies to --format bc1 only (opaque BC1), not '" + a.format + "'");
  a.mip.filter.kind = parse_filter_kind(a.chain.filter);
  a.mip.filter.sigma = a.chain.sigma;
  a.mip.wrap = parse_wrap_mode(a.wrap);
  a.mip.max_levels = a.chain.levels;
  a.mip.min_size = a.chain.min_size;
  a.mip.normal_map = a.normal_map;
  if (a.alpha_coverage >= 0.0f && !a.mips)
    throw Error(ErrorCode::bad_arguments, "--alpha-coverage applies to the mip chain: add --mips");
  if (a.alpha_coverage >= 0.0f && !(a.alpha_coverage > 0.0f && a.alpha_coverage <= 1.0f))
    throw Error(ErrorCode::bad_arguments, "--alpha-coverage " + std::to_string(a.alpha_coverage) + " is not in (0, 1]");
  if (a.alpha_coverage >= 0.0f) a.mip.alpha_coverage_ref = a.alpha_coverage;
  if (a.no_premultiply && !a.mips)
    throw Error(ErrorCode::bad_arguments, "--no-premultiply applies to the mip chain: add --mips");
  a.mip.premultiplied_alpha = !a.no_premultiply;
}

// LDR formats hold [0, 1]: float input outside it is clipped, which an HDR
// source rarely means. One warning per file, with the range and the way out.
void warn_if_clipped(const std::string& input, const ImageChains& in, TexelFormat format,
                     std::vector<std::string>& warnings) {
  if (format_info(format).is_float || in.chains[0][0].type() != PixelType::f32) return;
  float lo = 0.0f, hi = 1.0f;
  for (const std::vector<Image>& chain : in.chains)
    for (const Image& img : chain) {
      const float* p = reinterpret_cast<const float*>(img.data());
      const std::size_t n = img.byte_size() / sizeof(float);
      for (std::size_t i = 0; i < n; ++i) {
        lo = std::min(lo, p[i]);
        hi = std::max(hi, p[i]);
      }
    }
  if (lo >= 0.0f && hi <= 1.0f) return;
  char range[96];
  std::snprintf(range, sizeof range, "values from %g to %g", double(lo), double(hi));
  warnings.push_back(input + ": " + range + " are clipped to [0, 1] by " + format_info(format).name +
                     "; an HDR format keeps them (bc6h, bc6hs, astc-WxH-hdr), --clip says the clipping is meant");
}

// A colour image as linear f32 (alpha unchanged).
Image decode_to_linear(const Image& img, const ColorSpace& from) {
  Image out = Image::uninitialized(img.width(), img.height(), img.channels(), PixelType::f32);
  for_each_row_block(img.height(), 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      from.decode_row(img.data() + std::size_t(y) * img.row_stride(), img.type(), img.channels(), img.width(),
                      out.row<float>(y));
  });
  return out;
}

// The encoded level and its decoding as f32 images with the format's
// channels, on one scale ([0, 1]; SNORM mapped back from [-1, 1]); an ASTC
// normal map is compared as stored (X in RGB, Y in alpha).
ImageDifference encoding_error(const Image& level, const Texture& t, bool astc_normal_map) {
  const Image decoded = decode_texture_image(t, 0, 0, 0, PixelType::f32);
  const int channels = decoded.channels();
  const bool snorm = format_info(t.format).snorm;
  Image src = Image::uninitialized(level.width(), level.height(), channels, PixelType::f32);
  Image dec = Image::uninitialized(level.width(), level.height(), channels, PixelType::f32);
  const int n = level.channels();
  for (int y = 0; y < level.height(); ++y) {
    for (int x = 0; x < level.width(); ++x) {
      for (int c = 0; c < channels; ++c) {
        float v;
        if (astc_normal_map) {
          v = level.get(x, y, c < 3 ? 0 : n > 1 ? 1 : 0);  // stored X, X, X, Y
        } else if (channels <= 2) {
          v = c < n ? level.get(x, y, c) : 0.0f;  // BC4/BC5: the first channels, as data
        } else if (c < 3) {
          v = level.get(x, y, n >= 3 ? c : 0);  // gray fills RGB
        } else {
          v = n == 4 ? level.get(x, y, 3) : n == 2 ? level.get(x, y, 1) : 1.0f;
        }
        src.row<float>(y)[x * channels + c] = v;
        const float d = decoded.row<float>(y)[x * channels + c];
        dec.row<float>(y)[x * channels + c] = snorm ? (d + 1.0f) * 0.5f : d;
      }
    }
  }
  return compare_images(src.view(), dec.view());
}

Json::Value number_or_null(double v) { return std::isfinite(v) ? Json::Value(v) : Json::Value(); }

void run_compress(const CompressArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  check_dds_header_fits(a.dds_header, output);
  // --target web: downloads, so KTX2 outputs are Zstandard-supercompressed unless --zstd says.
  const int zstd = a.web_zstd && container_for_path(output) == ContainerKind::ktx2 ? 19 : a.zstd;
  zstd_level_for(zstd, output);  // checked before any work
  PhaseTimer phases(r);
  // A texture keeps its chains (the first --levels of them); --mips makes
  // new ones from level 0.
  ImageFileInfo info;
  ImageChains in = read_image_chains(input, &info, cli_read_options(), a.mips ? 1 : std::uint32_t(a.chain.levels));
  if (!a.mips && a.chain.levels > 0 && info.mip_levels <= 1) {
    throw Error(ErrorCode::bad_arguments, input + ": --levels keeps the first levels of an input's chain, and " +
                                              input + " has one level: add --mips to make a chain");
  }
  for (std::vector<Image>& chain : in.chains)
    for (Image& im : chain) {
      read_as_finite(input, im, r.warnings);
      apply_channel_options(a.channels, im);
    }
  phases.read_done();
  const PixelType input_type = in.chains[0][0].type();
  // Colour is sRGB unless --linear, a normal map, or float input.
  bool srgb = a.srgb || (!a.linear && !a.normal_map && input_type != PixelType::f32);
  // A full LDR format name says it: an sRGB format's input is sRGB colour,
  // a UNORM format's is data (as --linear).
  if (const auto t = exact_block_format(a.format); t && !format_info(*t).is_float) srgb = format_info(*t).srgb;
  const TexelFormat format = block_format_for(a.format, srgb);
  if (!a.size.rule.empty()) {
    if (in.chains[0].size() > 1) {
      throw Error(ErrorCode::bad_arguments, input + ": keeps its own " + std::to_string(in.chains[0].size()) +
                                                " levels, which --resize and the others would not match: add --mips "
                                                "to make a chain from the resized level 0");
    }
    for (std::vector<Image>& chain : in.chains)
      apply_size_options(a.size, chain[0], srgb ? "srgb" : "linear", a.normal_map);
  }
  if (!a.clip) warn_if_clipped(input, in, format, r.warnings);
  warn_if_dx10_for_dxt(a, format, output, r.warnings);
  if (!a.srgb && !a.normal_map)
    warn_if_normal_map_as_srgb(input, in.chains[0][0], format_info(format).srgb, r.warnings);
  warn_if_alpha_dropped(input, in.chains[0][0], format, r.warnings);
  // HDR formats hold linear values: 8/16-bit colour is decoded from sRGB
  // first (as data with --linear), so the chain and the encoder see light.
  if (format_info(format).is_float && input_type != PixelType::f32) {
    const ColorSpace from = srgb ? ColorSpace::srgb() : ColorSpace::linear();
    for (std::vector<Image>& chain : in.chains)
      for (Image& img : chain) img = decode_to_linear(img, from);
  }
  const auto t0 = std::chrono::steady_clock::now();
  TextureEncodeOptions options;
  options.encode.bc1_black = a.bc1_black;
  if (a.astc_effort >= 0.0f) options.encode.astc_effort = a.astc_effort;
  options.encode.progress = r.progress;
  options.normal_map = a.normal_map;
  options.transparent = a.transparent;
  // One chain per surface: a cubemap's faces and an array's layers (index
  // layer * faces + face), each level encoded as it is, or (--mips) encoded
  // as the new chain is filtered. Afterwards in.chains[0][0] holds level 0
  // as it was encoded.
  Texture t;
  if (a.mips) {
    MipOptions m = a.mip;
    m.color_space = format_info(format).srgb ? "srgb" : "linear";
    std::vector<Image> surfaces;
    for (std::vector<Image>& chain : in.chains) surfaces.push_back(std::move(chain[0]));
    t = compress_texture_mips(surfaces, m, in.layout(), format, a.q, options);
    in.chains[0][0] = std::move(surfaces[0]);
  } else {
    t = compress_texture(in.chains, in.layout(), format, a.q, options);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  phases.compute_done();
  write_texture(output, t, a.header, zstd_level_for(zstd, output));
  phases.write_done();
  std::ostringstream line;
  line << input << " -> " << output << ": " << format_info(format).name << ", " << t.levels << " level(s), quality "
       << a.quality << ", encoded in " << s << " s";
  if (a.mips && info.mip_levels > 1) {
    line << " (the input's " << info.mip_levels << " levels replaced by a chain made from its level 0)";
  }
  r.details["format"] = format_info(format).name;
  r.details["width"] = t.width;
  r.details["height"] = t.height;
  r.details["levels"] = t.levels;
  r.details["input_levels"] = info.mip_levels;
  r.details["quality"] = a.quality;
  r.details["encode_seconds"] = s;
  if (a.report) {
    const ImageDifference d = encoding_error(in.chains[0][0], t, a.normal_map && is_astc(format));
    Json::Value rep(Json::objectValue);
    rep["psnr"] = number_or_null(d.psnr());
    if (d.channels >= 3) rep["psnr_rgb"] = number_or_null(d.psnr_rgb());
    Json::Value per(Json::arrayValue);
    for (int c = 0; c < d.channels; ++c) per.append(number_or_null(d.psnr_channel(c)));
    rep["psnr_channels"] = per;
    rep["max_error"] = d.max_abs;
    if (format_info(format).is_float) rep["log_rmse_rgb"] = d.log_rmse_rgb();
    r.details["report"] = rep;
    char b[96];
    std::snprintf(b, sizeof b, ", PSNR %.2f dB", d.psnr());
    line << b;
    if (d.channels >= 3) {
      std::snprintf(b, sizeof b, " (RGB %.2f dB)", d.psnr_rgb());
      line << b;
    }
    if (format_info(format).is_float) {
      std::snprintf(b, sizeof b, ", log2 RMSE %.5f", d.log_rmse_rgb());
      line << b;
    }
  }
  r.line = line.str();
}

}  // namespace

void add_compress_command(CLI::App& app) {
  auto args = std::make_shared<CompressArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compress", "Block-compress images (BC1-BC7, ETC1, ETC2, EAC, ASTC) into DDS, KTX2, KTX1, PKM or .astc.");
  cmd->footer(
      "BC4 and EAC R11 store one channel, BC5 and EAC RG11 two (the red and green of the input; for a normal\n"
      "map its X and Y, the shader rebuilds Z). SNORM variants map the stored [0, 1] to [-1, 1]. Values are\n"
      "data: no transfer function. BC6H holds HDR RGB as half floats (bc6h: UF16, negatives stored as 0;\n"
      "bc6hs: SF16); alpha is dropped; 8/16-bit colour is decoded from sRGB first. ETC and EAC go to .ktx2 (the "
      "default for -o DIR/), .ktx, or .pkm (ETC1 and\n"
      "ETC2 RGB, one level). ASTC (astc-WxH: LDR, sRGB for colour; astc-WxH-hdr: HDR, linear) is searched by\n"
      "ARM's astc-encoder at the preset --quality names (fast: -fast, normal: -medium, high: -thorough,\n"
      "max: -exhaustive) and goes to .ktx2 (the default), .ktx or .astc (one level). See docs/compression.md.");
  add_batch_inputs(
      *cmd, args->io, "Input images",
      "Output texture (.dds, .ktx2, .ktx, .pkm, .astc), folder (DIR/: {stem}.dds each; .ktx2 for ETC/EAC/ASTC) or "
      "template ('out/{stem}.ktx2')");
  cmd->add_option("--format", args->format,
                  "bc1, bc1a (1-bit alpha), bc2, bc3, bc4, bc4s, bc5, bc5s, bc7, bc6h (HDR RGB, UF16), bc6hs (HDR, "
                  "signed: SF16); etc1, etc2, etc2a1 (punch-through alpha), "
                  "etc2a (EAC alpha), eac-r11, eac-r11s, eac-rg11, eac-rg11s; astc-4x4, astc-5x4, astc-5x5, astc-6x5, "
                  "astc-6x6, astc-8x5, astc-8x6, astc-8x8, astc-10x5, astc-10x6, astc-10x8, astc-10x10, astc-12x10, "
                  "astc-12x12, each also -hdr (astc-6x6-hdr); or --role")
      ->capture_default_str();
  cmd->add_option("--role", args->role,
                  "What the texture is, for the defaults the other options leave out: color, color-alpha, cutout, "
                  "normal, mask, height, hdr, ui (the table in docs/compression.md)");
  cmd->add_option("--target", args->target, "With --role: desktop (default), mobile, web");
  cmd->add_flag("--srgb", args->srgb, "BC1-BC3, BC7: write the sRGB format (the default for 8/16-bit colour input)");
  cmd->add_flag("--linear", args->linear, "The input is data: UNORM formats, linear mip filtering");
  cmd->add_option("--quality", args->quality, "fast, normal, high, max (widest search; slow)")->capture_default_str();
  cmd->add_flag(
      "--clip", args->clip,
      "Float input to an LDR format: clip values outside [0, 1] without the warning (an HDR format keeps them)");
  cmd->add_option("--astc-effort", args->astc_effort,
                  "ASTC: astc-encoder's numeric quality 0-100 in place of --quality's preset (0 -fastest, 10 -fast, "
                  "60 -medium, 98 -thorough, 99 -verythorough, 100 -exhaustive)")
      ->check(in_range(0, 100));
  cmd->add_flag("--mips,!--no-mips", args->mips_flag,
                "Make and compress a new mip chain from level 0 (mip options below). Without it (--no-mips, the "
                "default without --role) a texture input keeps every level, face and layer it has, each encoded as it "
                "is (--levels N: "
                "its first N), and an image gives one level; --role sets it unless given")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  cmd->add_flag("--normal-map", args->normal_map,
                "The input is a normal map: linear, renormalized mips; bc5/eac-rg11 store X and Y, bc3 the DXT5nm "
                "layout (X in alpha, Y in green, red 1, blue 0), astc astc-encoder's normal mode (X in RGB, Y in "
                "alpha)");
  cmd->add_option("--wrap", args->wrap, "Mip filter taps past the edges: clamp, repeat, mirror")->capture_default_str();
  cmd->add_option("--alpha-coverage", args->alpha_coverage,
                  "With --mips: keep the fraction of texels with alpha >= REF equal to level 0's in every level "
                  "(cutouts; 0.5 for bc1a and etc2a1, whose alpha is cut at 128), 0 < REF <= 1")
      ->check(in_range(0, 1, true));
  cmd->add_flag("--no-premultiply", args->no_premultiply,
                "With --mips: filter colour without weighting it by alpha (an alpha channel that holds data)");
  add_chain_options(*cmd, args->chain);
  add_channel_options(*cmd, args->channels);
  add_size_options(*cmd, args->size);
  cmd->add_option("--dds-header", args->dds_header, "auto, dx9, dx10")->capture_default_str();
  cmd->add_option("--zstd", args->zstd, "KTX2 output: Zstandard-supercompress each level at this level (1-22)")
      ->check(in_range(1, 22))
      ->group("Container");
  cmd->add_option(
         "--transparent-color", args->transparent_color,
         "Colour under alpha 0 (formats with alpha: bc1a, bc2, bc3, bc7, etc2a1, etc2a, astc): keep, bleed (from the "
         "visible texels), zero")
      ->capture_default_str();
  cmd->add_flag("--bc1-black", args->bc1_black,
                "bc1: dark texels may take the three-colour mode's black where that lowers the error (Direct3D "
                "reads alpha 0 there: for KTX2/Vulkan/OpenGL BC1 RGB, or shaders that ignore alpha)");
  cmd->add_flag("--report", args->report, "Decode level 0 again and report its PSNR (all channels, RGB, each channel)");
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "compress";
    std::string f = args->format;
    bool web = false;
    try {  // the format a --role picks (an error is validate's to report)
      CompressArgs probe = *args;
      apply_role(probe);
      f = probe.format;
      web = probe.web_zstd;
    } catch (const Error&) {
    }
    for (auto& ch : f) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    bool no_dds = false;  // DDS has no ETC or ASTC formats (an unknown name fails in validate)
    try {
      no_dds = format_info(block_format_for(f, false)).dxgi_format == 0;
    } catch (const Error&) {
    }
    c.default_extension = no_dds || web ? ".ktx2" : ".dds";  // DDS has no ETC or ASTC formats; the web takes KTX2
    c.input_extensions = image_extensions();
    c.validate = [args] { validate(*args); };
    c.plan = [](const InputFile&, const std::string& out) {
      container_for_path(out);  // a container extension, or an error now
      return std::vector<std::string>{out};
    };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_compress(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
