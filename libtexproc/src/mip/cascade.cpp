// The cascade: levels 1.. of a mip chain filtered together, a wave of
// level-1 rows at a time, each later level taking the rows whose sources
// are complete. A row of level k is computed by the same arithmetic from the
// same level k-1 rows as when whole levels are stored, so the bytes are the
// same; a row is freed once every row of the next level that reads it is
// done. Memory: a wave of level-1 rows and the filter's reach on each later
// level, instead of a float copy of level 1 (as large as an RGBA8 input).
#include <algorithm>
#include <cassert>
#include <climits>
#include <cstring>
#include <memory>

#include "mip/chain_rows.h"
#include "mip/resample.h"
#include "texproc/runtime.h"

namespace texproc::mip_rows {
namespace {

// For each row of a level, the distinct rows of the level below it reads
// (after wrap_index), in compressed-row form.
struct RowSources {
  std::vector<int> begin;  // rows + 1 entries
  std::vector<int> rows;

  RowSources() = default;
  RowSources(const AxisWeights& wy, int src_rows, WrapMode wrap) {
    begin.reserve(wy.dst_size + 1);
    begin.push_back(0);
    for (int y = 0; y < wy.dst_size; ++y) {
      const std::size_t start = rows.size();
      for (int k = 0; k < wy.taps; ++k) rows.push_back(wrap_index(wy.first[y] + k, src_rows, wrap));
      std::sort(rows.begin() + start, rows.end());
      rows.erase(std::unique(rows.begin() + start, rows.end()), rows.end());
      begin.push_back(int(rows.size()));
    }
  }
  const int* first(int y) const { return rows.data() + begin[y]; }
  const int* last(int y) const { return rows.data() + begin[y + 1]; }
};

// The float rows of one level that the next level has yet to read. Row
// buffers are recycled: a level holds at most a wave's worth at once.
class HeldRows {
 public:
  HeldRows(int width, int channels, const RowSources& readers_of_next, int rows)
      : row_floats_(std::size_t(width) * channels), slot_(rows, -1), readers_(rows, 0) {
    for (int j : readers_of_next.rows) ++readers_[j];
  }
  float* hold(int y) {
    int slot;
    if (free_.empty()) {
      slot = int(buffers_.size());
      buffers_.emplace_back(row_floats_);
    } else {
      slot = free_.back();
      free_.pop_back();
    }
    slot_[y] = slot;
    return buffers_[slot].data();
  }
  bool held(int y) const { return slot_[y] >= 0; }
  const float* get(int y) const { return buffers_[slot_[y]].data(); }
  // One more row of the next level has read row y.
  void read_once(int y) {
    if (--readers_[y] == 0) {
      free_.push_back(slot_[y]);
      slot_[y] = -1;
    }
  }

 private:
  std::size_t row_floats_;
  std::vector<FloatBuffer> buffers_;
  std::vector<int> free_;
  std::vector<int> slot_;     // per row: its buffer, or -1
  std::vector<int> readers_;  // per row: rows of the next level yet to read it
};

struct CascadeLevel {
  int width = 0, height = 0;
  AxisWeights wx, wy;
  RowSources sources;  // rows of the level below each row reads
  std::vector<char> done;
  std::vector<int> pending;  // levels >= 2: rows not yet computed, ascending
};

// Computes `rows` of level k (>= 1) into `held` (when a next level reads
// them) and the sink.
void compute_rows(const ChainSetup& s, const ConstImageView& input, std::vector<CascadeLevel>& L,
                  std::vector<std::unique_ptr<HeldRows>>& held, int k, const std::vector<int>& rows, MipRowSink& sink) {
  const int C = s.channels;
  CascadeLevel& lv = L[k];
  const int sw = k == 1 ? input.width : L[k - 1].width;
  const int sh = k == 1 ? input.height : L[k - 1].height;
  const std::size_t src_row = std::size_t(sw) * C;
  std::vector<float*> outs(rows.size(), nullptr);
  if (held[k]) {
    for (std::size_t i = 0; i < rows.size(); ++i) outs[i] = held[k]->hold(rows[i]);
  }
  for_each_row_block(int(rows.size()), kBlockRows, [&](int i0, int i1) {
    Scratch& sc = scratch();
    // Level 1 reads the input, decoded per block as whole-level filtering does.
    int lo = INT_MAX;
    if (k == 1) {
      int hi = INT_MIN;
      for (int i = i0; i < i1; ++i) {
        lo = std::min(lo, lv.wy.first[rows[i]]);
        hi = std::max(hi, lv.wy.first[rows[i]] + lv.wy.taps - 1);
      }
      sc.rows.resize(hi - lo + 1);
      sc.decoded.resize(sc.rows.size() * src_row);
      for (int j = lo; j <= hi; ++j) {
        float* d = sc.decoded.data() + (j - lo) * src_row;
        decode_input_row(s, input, wrap_index(j, sh, s.wrap), d);
        sc.rows[j - lo] = d;
      }
    }
    sc.row.resize(std::size_t(lv.wx.pad_before + sw + lv.wx.pad_after) * C);
    float* mid = sc.row.data() + std::size_t(lv.wx.pad_before) * C;
    sc.taps.resize(lv.wy.taps);
    for (int i = i0; i < i1; ++i) {
      const int y = rows[i];
      for (int t = 0; t < lv.wy.taps; ++t) {
        const int j = lv.wy.first[y] + t;
        sc.taps[t] = k == 1 ? sc.rows[j - lo] : held[k - 1]->get(wrap_index(j, sh, s.wrap));
      }
      vertical_pass(sc.taps.data(), lv.wy.weights.data() + std::size_t(y) * lv.wy.taps, lv.wy.taps, int(src_row), mid);
      for (int p = 1; p <= lv.wx.pad_before; ++p) {
        std::memcpy(mid - p * C, mid + wrap_index(-p, sw, s.wrap) * C, C * sizeof(float));
      }
      for (int p = 0; p < lv.wx.pad_after; ++p) {
        std::memcpy(mid + (sw + p) * C, mid + wrap_index(sw + p, sw, s.wrap) * C, C * sizeof(float));
      }
      float* out = outs[i];
      if (!out) {
        sc.level_row.resize(std::size_t(lv.width) * C);
        out = sc.level_row.data();
      }
      horizontal_pass(mid, C, lv.wx.first.data(), lv.wx.weights.data(), lv.wx.taps, lv.width, out);
      if (s.normal_map) renormalize_row(out, C, lv.width);
      encode_level_row(s, out, lv.width, 1.0f, sink.row(k, y));
      sink.row_done(k, y);
    }
  });
  for (int y : rows) {
    lv.done[y] = 1;
    if (k >= 2) {
      for (const int* j = lv.sources.first(y); j != lv.sources.last(y); ++j) held[k - 1]->read_once(*j);
    }
  }
}

}  // namespace

void cascade(const ChainSetup& s, const ConstImageView& input, int levels, const Filter& filter, MipRowSink& sink) {
  std::vector<CascadeLevel> L(levels);
  for (int k = 1; k < levels; ++k) {
    const int sw = k == 1 ? input.width : L[k - 1].width, sh = k == 1 ? input.height : L[k - 1].height;
    CascadeLevel& lv = L[k];
    lv.width = mip_level_dim(input.width, k);
    lv.height = mip_level_dim(input.height, k);
    lv.wx = compute_axis_weights(sw, lv.width, filter);
    lv.wy = compute_axis_weights(sh, lv.height, filter);
    lv.sources = RowSources(lv.wy, sh, s.wrap);
    lv.done.assign(lv.height, 0);
    if (k >= 2) {
      lv.pending.resize(lv.height);
      for (int y = 0; y < lv.height; ++y) lv.pending[y] = y;
    }
  }
  std::vector<std::unique_ptr<HeldRows>> held(levels);
  for (int k = 1; k + 1 < levels; ++k) {
    held[k] = std::make_unique<HeldRows>(L[k].width, s.channels, L[k + 1].sources, L[k].height);
  }
  // Waves of level-1 rows: big enough to keep every thread busy, small
  // enough that the rows held stay a sliver of the level.
  const int wave = kBlockRows * std::max(8, 4 * thread_limit());
  std::vector<int> rows;
  for (int y0 = 0; y0 < L[1].height; y0 += wave) {
    rows.clear();
    for (int y = y0; y < std::min(L[1].height, y0 + wave); ++y) rows.push_back(y);
    compute_rows(s, input, L, held, 1, rows, sink);
    for (int k = 2; k < levels; ++k) {
      CascadeLevel& lv = L[k];
      rows.clear();
      std::vector<int> waiting;
      for (int y : lv.pending) {
        bool ready = true;
        for (const int* j = lv.sources.first(y); ready && j != lv.sources.last(y); ++j) ready = L[k - 1].done[*j];
        (ready ? rows : waiting).push_back(y);
      }
      lv.pending.swap(waiting);
      if (!rows.empty()) compute_rows(s, input, L, held, k, rows, sink);
    }
  }
  // Level 1 ends with the last wave, and each later level within that wave.
  for (int k = 2; k < levels; ++k) assert(L[k].pending.empty());
}

}  // namespace texproc::mip_rows
