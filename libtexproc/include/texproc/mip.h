// texproc/mip.h: gamma-correct mip chains.
//
// Each level is filtered from the previous one in linear, premultiplied float
// (never from re-quantized bytes), with polyphase weights for odd sizes. See
// docs/mip.md for why level-to-level and what each option does.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "texproc/color.h"
#include "texproc/filters.h"
#include "texproc/image.h"

namespace texproc {

struct MipOptions {
  Filter filter;                    // default: Gaussian, sigma 0.5 destination texels
  WrapMode wrap = WrapMode::clamp;  // taps past the edges
  // Source color space; empty: sRGB for u8/u16 input, linear for f32 input.
  // Normal maps are always decoded as linear data.
  std::string color_space;
  // Color space of the written levels; empty: the source one, except that
  // f32 output from integer input is linear (scene-linear floats).
  std::string output_color_space;
  // Element type of the written levels; empty: the input's type.
  std::optional<PixelType> output_type;
  // Filter color premultiplied by alpha (channels 2 and 4). Off only for data
  // whose fourth channel is not coverage.
  bool premultiplied_alpha = true;
  // Where set (in (0, 1]): scale each level's alpha so that the fraction of
  // texels with alpha >= ref equals level 0's (NVTT's scaleAlphaForCoverage).
  std::optional<float> alpha_coverage_ref;
  // The input is a tangent-space normal map (RGB = XYZ * 0.5 + 0.5): filter
  // the vectors and renormalize each level. Alpha, if any, is filtered as
  // plain data.
  bool normal_map = false;
  int max_levels = 0;  // 0: all levels down to 1x1
  int min_size = 1;    // stop before a level whose larger side is < min_size
};

// Number of levels MipOptions produce for a width x height image.
int mip_level_count(int width, int height, int max_levels = 0, int min_size = 1);
// Size of `level`: max(1, floor(size / 2^level)) per axis.
int mip_level_dim(int size, int level);

struct MipChain {
  std::vector<Image> levels;          // level 0 first
  std::string color_space;            // of the stored levels
  std::vector<float> alpha_coverage;  // per level, when alpha_coverage_ref is set
  std::vector<float> alpha_scale;     // per level, the factor applied to alpha
};

// Builds the chain. Level 0 is the input converted to the output type and
// color space (a byte copy when they match). Throws Error{bad_arguments} for
// invalid options (normal maps need 3 or 4 channels, sigma out of range...).
// Output bytes are identical for any thread count.
MipChain generate_mips(const ConstImageView& image, const MipOptions& options);
// The same, taking ownership of `image`: when level 0 needs no conversion it
// becomes levels[0] without a copy.
MipChain generate_mips(Image&& image, const MipOptions& options);

// Receives the rows of levels 1.. of a chain as generate_mips_rows filters
// them.
class MipRowSink {
 public:
  virtual ~MipRowSink() = default;
  // Before any row: how many levels the chain has (level 0 included), and
  // the element type and channel count of every level.
  virtual void begin(int levels, PixelType type, int channels) {}
  // True to be given level 0 too (the input converted to the output type
  // and color space, as generate_mips's levels[0]), before the other levels.
  virtual bool wants_level0() const { return false; }
  // Where row y of `level` (>= 1, or 0 where wanted) goes: mip_level_dim(width, level) *
  // channels elements of the type. Each row of each level is asked for
  // once, in no fixed order, from several threads at once (for different
  // rows); the level's rows below it may still be coming.
  virtual void* row(int level, int y) = 0;
  // Row y of `level` is written (called by the thread that asked for it).
  virtual void row_done(int level, int y) {}
};

// The chain generate_mips builds, levels 1.. only, streamed into `sink`
// without holding it: a level's rows stay in float only until every row of
// the next level that reads them is done, so beside the input the memory is
// a few hundred rows (with alpha_coverage_ref set, one whole level in
// float, as its coverage must be known before it is written). Level 0 is
// the input converted as generate_mips converts it; the sink gets its rows
// only if it wants them. Returns the chain with no levels: its color space
// and coverage.
// The rows' bytes are generate_mips's, for any thread count.
MipChain generate_mips_rows(const ConstImageView& image, const MipOptions& options, MipRowSink& sink);

// ---- Resizing ----------------------------------------------------------------

struct ResizeOptions {
  Filter filter{FilterKind::lanczos3};  // widened by the scale when shrinking
  WrapMode wrap = WrapMode::clamp;      // taps past the edges
  std::string color_space;              // empty: sRGB for u8/u16, linear for f32
  bool premultiplied_alpha = true;      // as MipOptions
  bool normal_map = false;              // filter the vectors, renormalize (alpha as data)
};

// `image` resized to width x height, filtered as a mip level is (linear,
// premultiplied float, polyphase weights; the filter is widened by the
// scale when shrinking and kept at one texel when enlarging), in its type,
// channels and colour space. Never point sampling. Throws
// Error{bad_arguments} for sizes below 1 or invalid options.
Image resize_image(const ConstImageView& image, int width, int height, const ResizeOptions& options = {});

// The size --resize, --max-size, --pow2 and --multiple-of give a width x
// height image, applied in that order: `resize` W x H (0 for a side keeps
// the aspect ratio from the other), then at most `max_size` on the longer
// side (aspect kept, rounded, at least 1), then each side to a power of
// two (`pow2`: "up", "down", "nearest"; empty: none), then each side to
// a multiple of `multiple_of` (rounded up; 0 or 1: none).
struct SizeRule {
  int resize_width = 0, resize_height = 0;
  int max_size = 0;
  std::string pow2;
  int multiple_of = 0;
  bool empty() const { return !resize_width && !resize_height && !max_size && pow2.empty() && multiple_of <= 1; }
};
void apply_size_rule(const SizeRule& rule, int& width, int& height);

// The fraction of texels whose alpha (last channel) times `scale` is >= ref.
// Integer alpha is compared as value / max.
float alpha_coverage(const ConstImageView& image, float ref, float scale = 1.0f);

}  // namespace texproc
