// texproc sat: summed-area tables, box queries over them, and box blurs.
#include <cstdio>
#include <optional>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "batch.h"
#include "common.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"
#include "texproc/sat.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct SatArgs {
  BatchInputs io;
  std::string precision;
  // query
  std::string table;
  long long x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool json = false;
  // blur
  BatchInputs blur_io;
  std::string radius_map, wrap = "clamp", color_space;
  bool linear = false;
  float radius = 4.0f;
  // From the options, once (validate_blur):
  BoxBlurOptions blur;
  Image map;
};

std::string number(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::vector<std::string> plan_build(const std::string& output) {
  const std::string ext = fs::path(output).extension().string();
  if (ext != ".sat" && ext != ".exr") {
    throw Error(ErrorCode::unsupported, output + ": a table is written as .sat (exact) or .exr (float, for viewing)");
  }
  return {output};
}

void run_build(const SatArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  std::optional<SatPrecision> requested;
  if (!a.precision.empty()) requested = parse_sat_precision(a.precision);
  PhaseTimer phases(r);
  ImageFileInfo info;
  Image img = read_image(input, &info, cli_read_options());
  read_as_finite(input, img, r.warnings);
  phases.read_done();
  const SatPrecision p = requested ? *requested : default_sat_precision(img.type(), img.width(), img.height());
  const SummedAreaTable t = build_sat(img.view(), p);
  phases.compute_done();
  if (fs::path(output).extension() == ".sat") {
    write_sat_file(output, t);
  } else {
    // For viewing: the true sums S(x, y) as floats.
    Image view = Image::uninitialized(t.width, t.height, t.channels, PixelType::f32);
    for_each_row_block(t.height, 16, [&](int y0, int y1) {
      std::vector<double> s(t.channels);
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < t.width; ++x) {
          t.box_sum(0, 0, x + 1, y + 1, s.data());
          for (int c = 0; c < t.channels; ++c) view.row<float>(y)[x * t.channels + c] = float(s[c]);
        }
    });
    phases.compute_done();
    write_image(output, view.view(), cli_write_options());
  }
  phases.write_done();
  std::ostringstream line;
  line << input << " -> " << output << ": " << t.width << "x" << t.height << "x" << t.channels << " " << to_string(p);
  if (t.max_exact_box() > 0) line << ", exact for boxes up to " << t.max_exact_box() << " texels";
  if (t.error_bound() > 0) line << ", box sums within +-" << number(t.error_bound());
  r.line = line.str();
  r.details["width"] = t.width;
  r.details["height"] = t.height;
  r.details["channels"] = t.channels;
  r.details["precision"] = to_string(p);
}

int run_query(const SatArgs& a) {
  const SummedAreaTable t = read_sat_file(a.table);
  auto in = [](long long v, long long hi) { return v >= 0 && v <= hi; };
  if (!in(a.x0, t.width) || !in(a.x1, t.width) || !in(a.y0, t.height) || !in(a.y1, t.height) || a.x0 >= a.x1 ||
      a.y0 >= a.y1) {
    throw Error(ErrorCode::bad_arguments,
                a.table + ": box [" + std::to_string(a.x0) + ", " + std::to_string(a.x1) + ") x [" +
                    std::to_string(a.y0) + ", " + std::to_string(a.y1) + ") is empty or outside the " +
                    std::to_string(t.width) + "x" + std::to_string(t.height) +
                    " table (valid: 0 <= X0 < X1 <= width, 0 <= Y0 < Y1 <= height; X1, Y1 exclusive)");
  }
  const std::uint64_t area = std::uint64_t(a.x1 - a.x0) * std::uint64_t(a.y1 - a.y0);
  const std::uint64_t limit = t.max_exact_box();
  if ((t.precision == SatPrecision::u32 || t.precision == SatPrecision::u64) && area > limit) {
    throw Error(ErrorCode::bad_arguments, a.table + ": a box of " + std::to_string(area) + " texels is past what a " +
                                              to_string(t.precision) + " table of this input sums exactly (" +
                                              std::to_string(limit) + " texels); rebuild with --precision u64");
  }
  std::vector<double> sum(t.channels);
  t.box_sum(int(a.x0), int(a.y0), int(a.x1), int(a.y1), sum.data());
  // Integer tables sum integer codes; means are reported in those units too.
  if (a.json) {
    Json::Value box(Json::arrayValue), sums(Json::arrayValue), means(Json::arrayValue);
    for (long long v : {a.x0, a.y0, a.x1, a.y1}) box.append(Json::Int64(v));
    for (int c = 0; c < t.channels; ++c) {
      sums.append(sum[c]);
      means.append(sum[c] / double(area));
    }
    Json::Value j(Json::objectValue);
    j["box"] = box;
    j["texels"] = Json::UInt64(area);
    j["sum"] = sums;
    j["mean"] = means;
    j["error_bound"] = t.error_bound();
    std::cout << to_json(j, kExactDigits) << "\n";
  } else {
    for (int c = 0; c < t.channels; ++c) {
      std::cout << "channel " << c << ": sum " << number(sum[c]) << ", mean " << number(sum[c] / double(area)) << "\n";
    }
  }
  return 0;
}

void validate_blur(SatArgs& a) {
  a.blur.radius = a.radius;
  a.blur.wrap = parse_wrap_mode(a.wrap);
  if (a.blur.wrap == WrapMode::mirror)
    throw Error(ErrorCode::bad_arguments, "--wrap for sat blur: valid: clamp, repeat");
  a.blur.color_space = a.linear ? "linear" : a.color_space;
  if (!a.radius_map.empty()) {
    a.map = read_image(a.radius_map, nullptr, cli_read_options());
    record_input(a.radius_map);
  }
}

void run_blur(const SatArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  PhaseTimer phases(r);
  Image img = read_image(input, nullptr, cli_read_options());
  read_as_finite(input, img, r.warnings);
  phases.read_done();
  BoxBlurOptions o = a.blur;
  const ConstImageView mv = a.map.view();
  if (!a.map.empty()) o.radius_map = &mv;
  const Image out = box_blur(img.view(), o);
  phases.compute_done();
  write_image(output, out.view(), cli_write_options());
  phases.write_done();
  r.line = input + " -> " + output + ": box blur radius " + number(a.radius) +
           (a.radius_map.empty() ? "" : " x " + a.radius_map) + ", wrap " + a.wrap;
  r.details["width"] = img.width();
  r.details["height"] = img.height();
}

}  // namespace

void add_sat_command(CLI::App& app) {
  auto args = std::make_shared<SatArgs>();
  CLI::App* cmd = app.add_subcommand("sat", "Build a summed-area table; query boxes; box-blur with it.");
  cmd->footer(
      "texproc sat IN -o OUT.sat|OUT.exr [--precision u32|u64|f32|f64]\n"
      "texproc sat query TABLE.sat X0 Y0 X1 Y1 [--json]     (X1, Y1 exclusive)\n"
      "texproc sat blur IN -o OUT --radius R [--radius-map MAP] [--wrap clamp|repeat]\n"
      "Tables sum the stored values (8/16-bit codes, or floats). See docs/sat.md for the precision table.");
  cmd->require_subcommand(0, 1);
  add_batch_inputs(*cmd, args->io, "Input images",
                   "Output table: .sat (exact, raw) or .exr (float, for viewing), folder (DIR/: {stem}.sat each) or "
                   "template",
                   false);
  cmd->add_option("--precision", args->precision,
                  "Element type: u32, u64 (wrapping integers), f32 (mean subtracted), f64; default: the smallest "
                  "that is exact for every box of the input");
  add_common_options(*cmd);

  CLI::App* q = cmd->add_subcommand("query", "Sum and mean over a box [X0, X1) x [Y0, Y1) of a .sat table.");
  q->add_option("table", args->table, "A .sat file")->required();
  q->add_option("x0", args->x0, "Left column (inclusive)")->required();
  q->add_option("y0", args->y0, "Top row (inclusive)")->required();
  q->add_option("x1", args->x1, "Right column (exclusive)")->required();
  q->add_option("y1", args->y1, "Bottom row (exclusive)")->required();
  q->add_flag("--json", args->json, "Print {\"sum\": [...], \"mean\": [...], ...}");

  CLI::App* b = cmd->add_subcommand("blur", "Box blur of any radius at constant cost per texel, gamma-correct.");
  add_batch_inputs(*b, args->blur_io, "Input images",
                   "Output image, folder (DIR/: same name each) or template ('blurred/{name}')");
  b->add_option("--radius", args->radius, "Half-width in texels: a box of 2R+1; fractional radii blend")
      ->check(in_range(0, 1e6))
      ->capture_default_str();
  b->add_option("--radius-map", args->radius_map, "Per-texel radius: R times the map's first channel in [0, 1]");
  b->add_option("--wrap", args->wrap, "Texels past the edges: clamp, repeat")->capture_default_str();
  b->add_option("--colorspace", args->color_space, "Source color space (default: srgb for 8/16-bit, linear for float)");
  b->add_flag("--linear", args->linear, "The input is data: no transfer function");
  add_common_options(*b);

  set_runner(*cmd, [args, cmd, q, b] {
    if (q->parsed()) {
      ThreadLimit threads(run_options().threads);
      return run_query(*args);
    }
    BatchCommand c;
    if (b->parsed()) {
      c.name = "sat blur";
      c.default_extension = "";  // the input's
      c.input_extensions = image_extensions();
      c.validate = [args] { validate_blur(*args); };
      c.plan = [](const InputFile&, const std::string& out) { return std::vector<std::string>{out}; };
      c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_blur(*args, in, out, r); };
      return run_batch(c, args->blur_io);
    }
    if (args->io.inputs.empty() && args->io.file_list.empty()) {
      throw Error(ErrorCode::bad_arguments,
                  "sat needs input images and -o OUT.sat|OUT.exr|DIR/ (or: sat query, sat blur)");
    }
    if (args->io.output.empty()) throw Error(ErrorCode::bad_arguments, "sat: -o OUT.sat|OUT.exr|DIR/ is required");
    c.name = "sat";
    c.default_extension = ".sat";
    c.input_extensions = image_extensions();
    c.validate = [args] {
      if (!args->precision.empty()) parse_sat_precision(args->precision);
    };
    c.plan = [](const InputFile&, const std::string& out) { return plan_build(out); };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_build(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
