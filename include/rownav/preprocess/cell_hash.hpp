#pragma once
/// @file cell_hash.hpp Integer grid keys and an open-addressing hash from a cell key to a dense
/// index, with buffers reused across frames (no std::map, no per-frame allocation in steady
/// state). Shared by the voxel grid and the radius outlier filter.
#include <cstdint>
#include <vector>

namespace rownav::preprocess {

/// Floor of v as an int without a libm call (v must be within int range).
inline int fast_floor(float v) {
  const int i = static_cast<int>(v);
  return i - static_cast<int>(v < static_cast<float>(i));
}

/// Largest |cell index| per axis that cell_key packs (21 bits per axis).
inline constexpr int kMaxCellIndex = (1 << 20) - 1;

/// Cell index floor(v) of a scaled coordinate; false (i untouched) when it does not fit
/// cell_key or v is NaN / Inf.
inline bool cell_index(float v, int& i) {
  if (!(v > -static_cast<float>(kMaxCellIndex) && v < static_cast<float>(kMaxCellIndex)))
    return false;
  i = fast_floor(v);
  return true;
}

/// Packs three cell indices (each in [-kMaxCellIndex, kMaxCellIndex]) into 63 bits.
inline std::uint64_t cell_key(int ix, int iy, int iz = 0) {
  constexpr std::int64_t off = std::int64_t{1} << 20;
  return (static_cast<std::uint64_t>(ix + off) << 42) |
         (static_cast<std::uint64_t>(iy + off) << 21) | static_cast<std::uint64_t>(iz + off);
}

/// Open-addressing (linear probing) map from a 63-bit key to a 32-bit value.
class CellHash {
 public:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

  /// Empties the map, with room for `expected` keys at load <= 0.5 (it grows when needed; a
  /// small table stays in cache, so pass the expected number of distinct keys, not of points).
  void reset(std::size_t expected) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    if (cap != keys_.size()) {
      keys_.assign(cap, kEmpty);
      values_.assign(cap, 0);
      used_.clear();
      used_.reserve(cap / 2);
      set_mask();
    } else {
      for (const auto s : used_) keys_[s] = kEmpty;
      used_.clear();
    }
  }
  /// Number of keys stored.
  std::size_t size() const { return used_.size(); }

  /// Value of `key`; inserts `value_if_new` when absent (`inserted` tells which).
  std::uint32_t find_or_insert(std::uint64_t key, std::uint32_t value_if_new, bool& inserted) {
    std::size_t s = slot(key);
    while (true) {
      if (keys_[s] == key) {
        inserted = false;
        return values_[s];
      }
      if (keys_[s] == kEmpty) {
        if (2 * (used_.size() + 1) > keys_.size()) {
          grow();
          return find_or_insert(key, value_if_new, inserted);
        }
        keys_[s] = key;
        values_[s] = value_if_new;
        used_.push_back(static_cast<std::uint32_t>(s));
        inserted = true;
        return value_if_new;
      }
      s = (s + 1) & mask_;
    }
  }

  /// Value of `key`, or kNone.
  std::uint32_t find(std::uint64_t key) const {
    std::size_t s = slot(key);
    while (true) {
      if (keys_[s] == key) return values_[s];
      if (keys_[s] == kEmpty) return kNone;
      s = (s + 1) & mask_;
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  void set_mask() {
    mask_ = keys_.size() - 1;
    shift_ = 64;
    for (std::size_t c = keys_.size(); c > 1; c >>= 1) --shift_;
  }
  /// Doubles the table and re-inserts every key (rare: only when `expected` was too small).
  void grow() {
    std::vector<std::uint64_t> old_keys(keys_.size() * 2, kEmpty);
    std::vector<std::uint32_t> old_values(keys_.size() * 2, 0);
    old_keys.swap(keys_);
    old_values.swap(values_);
    set_mask();
    used_.clear();
    for (std::size_t s = 0; s < old_keys.size(); ++s) {
      if (old_keys[s] == kEmpty) continue;
      std::size_t t = slot(old_keys[s]);
      while (keys_[t] != kEmpty) t = (t + 1) & mask_;
      keys_[t] = old_keys[s];
      values_[t] = old_values[s];
      used_.push_back(static_cast<std::uint32_t>(t));
    }
  }
  std::size_t slot(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::vector<std::uint32_t> used_;
  std::size_t mask_ = 0;
  int shift_ = 60;
};

}  // namespace rownav::preprocess
