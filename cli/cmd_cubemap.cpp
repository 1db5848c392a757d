// texproc cubemap: environment maps from panoramas, faces, crosses and
// strips; seamless mips; GGX specular and diffuse irradiance for
// image-based lighting; spherical harmonics; a preview.
#include <algorithm>
#include <cstring>
#include <cstdio>
#include <cmath>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "batch.h"
#include "commands.h"
#include "common.h"
#include "cubemap_cli.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/metrics.h"
#include "texproc/texture.h"
#include "texproc/color.h"
#include "texproc/container.h"
#include "texproc/cubemap.h"
#include "texproc/error.h"
#include "texproc/tools.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

namespace fs = std::filesystem;

namespace texproc::cli {

namespace cube_cli {
Target target_for(const CubemapArgs& a, const std::string& output) {
  if (a.target != Target::automatic) return a.target;
  return is_container_path(output) ? Target::cube : Target::cross;
}
}  // namespace cube_cli

namespace {

using namespace cube_cli;

Target parse_target(const std::string& s) {
  static const std::pair<const char*, Target> kNames[] = {
      {"auto", Target::automatic},    {"cube", Target::cube},   {"cross", Target::cross},  {"hcross", Target::cross},
      {"vcross", Target::vcross},     {"strip", Target::strip}, {"hstrip", Target::strip}, {"vstrip", Target::vstrip},
      {"equirect", Target::equirect}, {"faces", Target::faces}};
  for (const auto& [name, t] : kNames)
    if (s == name) return t;
  throw Error(ErrorCode::bad_arguments,
              "--to " + s + ": valid: auto, cube, cross (= hcross), vcross, strip (= hstrip), vstrip, equirect, faces");
}

Ibl parse_ibl(const std::string& s) {
  if (s == "none") return Ibl::none;
  if (s == "specular") return Ibl::specular;
  if (s == "irradiance") return Ibl::irradiance;
  if (s == "both") return Ibl::both;
  throw Error(ErrorCode::bad_arguments, "--ibl " + s + ": valid: none, specular, irradiance, both");
}

void validate(CubemapArgs& a) {
  a.target = parse_target(a.to);
  a.mode = parse_ibl(a.ibl);
  a.flip_axis = parse_cube_flip(a.flip);
  a.header = parse_dds_header(a.dds_header);
  if (a.layout != "auto") parse_cube_layout(a.layout);
  a.q = parse_quality(a.quality);
  if (is_block_format(a.format)) {
    TexelFormat f;
    try {
      f = block_format_for(a.format, false);
    } catch (const Error&) {
      throw Error(ErrorCode::bad_arguments, "--format " + a.format +
                                                ": valid: rgba8, rgba16f, rgba32f, or a block format (bc6h, bc6hs, "
                                                "bc7, bc1, bc3, etc2, etc2a, astc-WxH, astc-WxH-hdr)");
    }
    if (format_info(f).channels < 3) {
      throw Error(ErrorCode::bad_arguments,
                  "--format " + a.format + " holds " + std::to_string(format_info(f).channels) +
                      " channel(s); a cube map's colour needs RGB (bc6h or astc-WxH-hdr for HDR, bc7 or astc-WxH)");
    }
  }
  if (a.size < 0 || a.size > 16384) throw Error(ErrorCode::bad_arguments, "--size: a face of 1 to 16384 texels");
  if (a.irradiance_size < 1 || a.irradiance_size > 1024) {
    throw Error(ErrorCode::bad_arguments, "--irradiance-size: 1 to 1024");
  }
  if (a.samples < 1 || a.samples > 65536) throw Error(ErrorCode::bad_arguments, "--samples: 1 to 65536");
  if (!(a.exposure > 0.0f)) throw Error(ErrorCode::bad_arguments, "--exposure must be positive");
  if (!a.faces.empty()) {
    if (a.faces.size() != 6) {
      throw Error(ErrorCode::bad_arguments,
                  "--faces takes six images, +X -X +Y -Y +Z -Z; got " + std::to_string(a.faces.size()));
    }
    if (!a.io.inputs.empty() || !a.io.file_list.empty()) {
      throw Error(ErrorCode::bad_arguments, "--faces replaces the input: give either IN or --faces");
    }
    a.io.inputs = {a.faces[0]};
  }
  if (a.io.inputs.empty() && a.io.file_list.empty()) {
    throw Error(ErrorCode::bad_arguments,
                "cubemap needs an input (a panorama, cross, strip or cube texture) or --faces");
  }
  if (a.io.output.empty()) throw Error(ErrorCode::bad_arguments, "cubemap: -o OUT.ktx2|.dds|.exr|DIR/ is required");
  a.output_is_folder = a.io.output.back() == '/' || fs::is_directory(a.io.output);
  if (a.target == Target::automatic && a.output_is_folder) a.target = Target::faces;
  if (a.mode == Ibl::irradiance && a.mips)
    throw Error(ErrorCode::bad_arguments, "--mips has no meaning with --ibl irradiance");
  if (!a.irradiance_path.empty() && a.mode != Ibl::both) {
    throw Error(ErrorCode::bad_arguments,
                "--irradiance FILE goes with --ibl both (with --ibl irradiance, -o is the map)");
  }
  if (!a.sh_path.empty() && fs::path(a.sh_path).extension() != ".json") {
    throw Error(ErrorCode::bad_arguments, "--sh " + a.sh_path + ": the coefficients are written as .json");
  }
  if (!a.preview_path.empty() && fs::path(a.preview_path).extension() != ".png") {
    throw Error(ErrorCode::bad_arguments, "--preview " + a.preview_path + ": the preview is a .png");
  }
  for (const std::string& f : a.faces) record_input(f);
}

// Where a folder output's images go: the input's extension, or for inputs
// that are containers or lossy, .exr for float and .png otherwise.
std::string image_extension_for(const std::string& input, const std::string& output) {
  std::string ext = fs::path(output).extension().string();
  if (ext == ".jpg" || ext == ".jpeg" || is_container_path(output) || ext.empty()) {
    const ImageFileInfo info = probe_image(input, cli_read_options());
    ext = info.type == PixelType::f32 ? ".exr" : ".png";
  }
  return ext;
}

std::string with_suffix(const std::string& output, const std::string& suffix, const std::string& ext) {
  const fs::path p(output);
  return (p.parent_path() / (p.stem().string() + suffix + ext)).string();
}

// OUT gets a chain of levels (else one level).
bool writes_chain(const CubemapArgs& a) { return a.mips || a.mode == Ibl::specular || a.mode == Ibl::both; }

// The files one cube map goes to under `output`: the container, the image,
// or six faces {stem}_px{ext} ... {stem}_nz{ext}; `suffix` goes after the stem.
std::vector<std::string> files_for(const CubemapArgs& a, const std::string& input, const std::string& output,
                                   const std::string& suffix, bool chain) {
  const Target t = target_for(a, output);
  if (t == Target::cube) {
    container_for_path(output);  // a container extension, or an error now
    return {with_suffix(output, suffix, fs::path(output).extension().string())};
  }
  if (is_container_path(output)) {
    throw Error(ErrorCode::bad_arguments, output + ": --to " + a.to + " writes images; a cube texture is --to cube");
  }
  const std::string ext = image_extension_for(input, output);
  if (chain && ext != ".exr" && ext != ".tif" && ext != ".tiff") {
    throw Error(ErrorCode::bad_arguments,
                output +
                    ": a chain of levels (--mips, --ibl specular) in an image file needs .exr or .tif (one "
                    "MIP-mapped file a face or layout), or a cube texture (.ktx2, .dds, .ktx)");
  }
  if (t != Target::faces) return {with_suffix(output, suffix, ext)};
  std::vector<std::string> names;
  for (const char* f : kFaceNames) names.push_back(with_suffix(output, suffix + "_" + f, ext));
  return names;
}

// --irradiance, --sh and --preview take templates as -o does.
Plan make_plan(const CubemapArgs& a, const InputFile& in, const std::string& output) {
  auto named = [&](const std::string& path) { return is_template(path) ? expand_template(path, in) : path; };
  Plan p;
  p.main = files_for(a, in.path, output, "", writes_chain(a));
  if (a.mode == Ibl::both) {
    p.irradiance = a.irradiance_path.empty() ? files_for(a, in.path, output, "_irradiance", false)
                                             : files_for(a, in.path, named(a.irradiance_path), "", false);
  }
  p.sh = a.sh_path.empty() ? "" : named(a.sh_path);
  p.preview = a.preview_path.empty() ? "" : named(a.preview_path);
  return p;
}

// ---- Reading ------------------------------------------------------------------

Source read_source(const CubemapArgs& a, const std::string& input, FileReport& r, PhaseTimer& phases) {
  CubemapReadOptions o;
  if (a.layout != "auto") o.layout = parse_cube_layout(a.layout);
  o.size = a.size;
  o.flip = a.flip_axis;
  if (a.linear) {
    o.color_space = ColorSpace::linear();
  } else if (!a.color_space.empty()) {
    o.color_space = ColorSpace::from_name(a.color_space);
  }
  o.read = cli_read_options();
  CubemapSource c;
  if (a.faces.empty()) {
    c = read_cubemap(input, o);
  } else {
    std::array<std::string, 6> faces;
    std::copy(a.faces.begin(), a.faces.begin() + 6, faces.begin());
    c = read_cubemap_faces(faces, o);
  }
  phases.read_done();
  if (!a.faces.empty()) r.inputs.insert(r.inputs.end(), c.files.begin(), c.files.end());
  r.warnings.insert(r.warnings.end(), c.warnings.begin(), c.warnings.end());
  return Source{std::move(c), a.faces.empty() ? input : a.faces[0]};
}

void run_cubemap(const CubemapArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  try {
    PhaseTimer phases(r);
    const Plan plan = a.plans.at(input);
    if (target_for(a, output) == Target::cube) {
      zstd_level_for(a.zstd, output);
      check_dds_header_fits(a.dds_header, output);
    } else if (a.zstd != 0 || a.dds_header != "auto") {
      throw Error(ErrorCode::bad_arguments, output + ": --zstd and --dds-header are for cube textures (.ktx2, .dds)");
    }
    if (is_block_format(a.format)) {
      for (const std::vector<std::string>* files : {&plan.main, &plan.irradiance}) {
        if (!files->empty() && target_for(a, (*files)[0]) != Target::cube) {
          throw Error(ErrorCode::bad_arguments, (*files)[0] + ": --format " + a.format +
                                                    " is a texture format: write a cube texture (.ktx2, .dds, .ktx)");
        }
      }
    }
    Source s = read_source(a, input, r, phases);
    const int levels = a.levels;
    Cubemap& env = s.cube;  // its level 0 is the source of the lighting below
    if (a.mips) generate_cube_mips(env, levels);
    Cubemap specular, irradiance;
    if (a.mode == Ibl::specular || a.mode == Ibl::both) {
      SpecularOptions so;
      so.size = a.size;  // 0: the library's default, the cube's size up to 256
      so.levels = levels;
      so.samples = a.samples;
      specular = prefilter_specular(env, so);
    }
    if (a.mode == Ibl::irradiance || a.mode == Ibl::both) irradiance = irradiance_cubemap(env, a.irradiance_size);
    phases.compute_done();
    const Cubemap& main = a.mode == Ibl::specular || a.mode == Ibl::both ? specular
                          : a.mode == Ibl::irradiance                    ? irradiance
                                                                         : env;
    const std::vector<double> errors = write_environment(a, s, main, plan.main, a.mode != Ibl::none, r.warnings);
    std::vector<double> irradiance_errors;
    if (!plan.irradiance.empty())
      irradiance_errors = write_environment(a, s, irradiance, plan.irradiance, true, r.warnings);
    if (!plan.sh.empty()) write_sh(plan.sh, project_sh9(env));
    if (!plan.preview.empty()) {
      const Image p = render_cube_preview(env, specular.levels.empty() ? nullptr : &specular, a.exposure);
      write_image(plan.preview, p.view(), cli_write_options());
    }
    phases.write_done();
    std::ostringstream line;
    line << input << " -> " << output << ": " << s.layout << " -> cube " << main.size() << ", " << main.levels.size()
         << (main.levels.size() == 1 ? " level" : " levels");
    if (a.mode != Ibl::none) line << ", " << a.ibl << " IBL";
    if (!errors.empty()) {
      const bool hdr = format_info(cube_format(a, s, a.mode != Ibl::none)).is_float;
      line << ", " << a.format << " error per level (" << (hdr ? "log2 RMSE" : "PSNR dB") << "):";
      Json::Value per(Json::arrayValue);
      for (double e : errors) {
        char b[32];
        std::snprintf(b, sizeof b, hdr ? " %.4f" : " %.2f", e);
        line << b;
        per.append(std::isfinite(e) ? Json::Value(e) : Json::Value());
      }
      r.details[hdr ? "level_log2_rmse" : "level_psnr"] = per;
    }
    if (!irradiance_errors.empty()) {
      const bool hdr = format_info(cube_format(a, s, true)).is_float;
      Json::Value per(Json::arrayValue);
      for (double e : irradiance_errors) per.append(std::isfinite(e) ? Json::Value(e) : Json::Value());
      r.details[hdr ? "irradiance_log2_rmse" : "irradiance_psnr"] = per;
    }
    if (!plan.irradiance.empty()) line << ", irradiance " << plan.irradiance[0];
    if (!plan.sh.empty()) line << ", SH " << plan.sh;
    if (!plan.preview.empty()) line << ", preview " << plan.preview;
    r.line = line.str();
    r.details["source"] = s.layout;
    r.details["size"] = main.size();
    r.details["levels"] = Json::UInt(main.levels.size());
    if (target_for(a, output) == Target::cube)
      r.details["format"] = format_info(cube_format(a, s, a.mode != Ibl::none)).name;
    if (a.report) {
      Json::Value seams(Json::arrayValue);
      for (const CubeLevel& l : main.levels) {
        const SeamStats st = measure_seams(l);
        Json::Value v;
        v["size"] = l.size;
        v["edge_step"] = st.edge_step;
        v["near_edge_step"] = st.near_edge_step;
        v["interior_step"] = st.interior_step;
        seams.append(v);
      }
      r.details["seams"] = seams;
    }
  } catch (const Error& e) {
    // The batch puts the input in front of a message; with --faces the
    // input is the +X face, so name the set, unless a face is named already.
    if (a.faces.empty()) throw;
    const std::string what = e.what();
    for (const std::string& f : a.faces)
      if (what.rfind(f, 0) == 0) throw;
    throw Error(e.code(), "--faces " + a.faces[0] + " ...: " + what);
  }
}

}  // namespace

void add_cubemap_command(CLI::App& app) {
  auto args = std::make_shared<CubemapArgs>();
  CLI::App* cmd = app.add_subcommand("cubemap", "Make cube maps (environment maps) and image-based lighting.");
  cmd->footer(
      "texproc cubemap IN -o OUT.ktx2|.dds|.ktx|.exr|.png|DIR/ [--size N] [--mips] [--ibl specular|irradiance|both]\n"
      "texproc cubemap --faces PX NX PY NY PZ NZ -o OUT ...\n"
      "IN: a 2:1 panorama (equirectangular), a cross (4:3, 3:4), a strip (6:1, 1:6), or a cube texture.\n"
      "OUT: a cube texture (.ktx2, .dds, .ktx), a cross image (.exr, .png, ...), six faces (DIR/ or --to faces:\n"
      "{stem}_px ... _nz), or a panorama (--to equirect). Faces follow Vulkan/OpenGL/D3D: +X -X +Y -Y +Z -Z.\n"
      "--mips: seamless (filtered over the sphere, across the face edges). --ibl specular: GGX prefiltered chain,\n"
      "roughness = level / (levels - 1); irradiance: cosine-convolved map. See docs/cubemap.md.");
  add_batch_inputs(*cmd, args->io, "Input panoramas, crosses, strips or cube textures",
                   "Output file, folder (DIR/: six faces each) or template ('env/{stem}.ktx2')", false);
  cmd->add_option("--faces", args->faces, "Six face images instead of IN: +X -X +Y -Y +Z -Z")->expected(6);
  cmd->add_option("--layout", args->layout,
                  "Input layout: auto (by aspect ratio), equirect, hcross, vcross, hstrip, vstrip")
      ->capture_default_str();
  cmd->add_option("--to", args->to,
                  "What OUT holds: auto (a cube texture for .ktx2/.dds/.ktx, six faces for DIR/, a cross otherwise), "
                  "cube, cross, vcross, strip, vstrip, equirect, faces")
      ->capture_default_str();
  cmd->add_option("--size", args->size, "Face size (default: a panorama's width / 4 as a power of two; a cross's face)")
      ->check(in_range(1, 16384));
  cmd->add_flag("--mips", args->mips, "A seamless mip chain down to 1x1");
  cmd->add_option("--levels", args->levels, "At most this many levels (with --mips or --ibl specular)")
      ->check(in_range(0, 32));
  cmd->add_option("--flip", args->flip, "Mirror a world axis of the source: none, x, y, z (z: left-handed engines)")
      ->capture_default_str();
  cmd->add_option("--format", args->format,
                  "Cube texture format: rgba8 (sRGB for sRGB input), rgba16f, rgba32f (default: rgba16f for float "
                  "input and IBL, rgba8 otherwise), or a block format as compress names them: bc6h, bc6hs, "
                  "astc-WxH-hdr (HDR), bc7, bc1, bc3, etc2, etc2a, astc-WxH (sRGB for sRGB input); every map written "
                  "(the cube and its chain, the specular chain, the irradiance map) gets it, and the error of each "
                  "level is reported");
  cmd->add_option("--quality", args->quality, "With a block --format: fast, normal, high, max")->capture_default_str();
  cmd->add_option("--colorspace", args->color_space,
                  "Source color space (default: srgb for 8/16-bit, linear for float)");
  cmd->add_flag("--linear", args->linear, "The input is data: no transfer function");
  cmd->add_option("--equirect-width", args->equirect_width, "--to equirect: the panorama's width (default 4 x size)")
      ->check(in_range(4, 16384));
  CLI::App& g = *cmd;
  g.add_option("--ibl", args->ibl, "Image-based lighting: none, specular, irradiance, both")
      ->capture_default_str()
      ->group("Lighting");
  g.add_option("--irradiance", args->irradiance_path,
               "--ibl both: the irradiance map's file or template ('ibl/{stem}_diffuse.ktx2'; default "
               "{stem}_irradiance{ext} beside OUT)")
      ->group("Lighting");
  g.add_option("--irradiance-size", args->irradiance_size, "Irradiance map face size")
      ->check(in_range(1, 4096))
      ->capture_default_str()
      ->group("Lighting");
  g.add_option("--samples", args->samples, "Importance samples per texel where the GGX lobe is sampled")
      ->check(in_range(1, 1 << 20))
      ->capture_default_str()
      ->group("Lighting");
  g.add_option("--sh", args->sh_path,
               "Write the 9 spherical-harmonic coefficients of the radiance (JSON; a template such as "
               "'ibl/{stem}_sh.json' for several inputs)")
      ->group("Lighting");
  g.add_option("--preview", args->preview_path,
               "Write a PNG: every level's cross and lit spheres (a template such as 'previews/{stem}.png' for "
               "several inputs)")
      ->group("Lighting");
  g.add_option("--exposure", args->exposure, "Preview exposure (a multiplier)")
      ->check(in_range(0, 1e9, true))
      ->capture_default_str()
      ->group("Lighting");
  cmd->add_option("--dds-header", args->dds_header, "DDS header: auto, dx9, dx10")
      ->capture_default_str()
      ->group("Container");
  cmd->add_option("--zstd", args->zstd, "KTX2 output: Zstandard-supercompress each level (1-22)")
      ->check(in_range(1, 22))
      ->group("Container");
  cmd->add_flag("--report", args->report, "With --json: seam figures per level (steps across edges and inside)");
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "cubemap";
    c.default_extension = ".ktx2";
    c.input_extensions = image_extensions();
    c.validate = [args] {
      validate(*args);
      if (args->target == Target::faces && args->output_is_folder) {
        // DIR/: {stem}{ext} there, the faces named from it.
        args->io.output = (fs::path(args->io.output) / "{stem}").string();
      }
    };
    c.plan = [args](const InputFile& in, const std::string& out) {
      // Planned once per file before any work; run_cubemap reads it back.
      return args->plans.insert_or_assign(in.path, make_plan(*args, in, out)).first->second.all();
    };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_cubemap(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
