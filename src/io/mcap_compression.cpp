// MCAP chunk compression: none, zstd, lz4 frames (io/mcap_compression.hpp).
#include "rownav/io/mcap_compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>

namespace rownav::io::mcap {

namespace {

/// zstd's default level: rosbag2's and the MCAP CLI's "fast" default trade-off.
constexpr int kZstdLevel = 3;

/// LZ4's largest expansion: a 255-byte run per input byte (lz4 block format).
constexpr std::uint64_t kLz4MaxRatio = 255;

std::vector<std::uint8_t> zstd_decompress(std::span<const std::uint8_t> data, std::uint64_t size) {
  // The frame header's content size, when it has one, must be the chunk's (checked before
  // allocating what a corrupt size field announces).
  const unsigned long long declared = ZSTD_getFrameContentSize(data.data(), data.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) throw CompressionError("zstd: not a zstd frame");
  if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != size)
    throw CompressionError("zstd: the frame holds " + std::to_string(declared) +
                           " bytes, the chunk announces " + std::to_string(size));
  std::vector<std::uint8_t> out(size);
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), data.data(), data.size());
  if (ZSTD_isError(n))
    throw CompressionError(std::string("zstd: ") + ZSTD_getErrorName(n));
  if (n != size)
    throw CompressionError("zstd: " + std::to_string(n) + " bytes instead of " +
                           std::to_string(size));
  return out;
}

std::vector<std::uint8_t> lz4_decompress(std::span<const std::uint8_t> data, std::uint64_t size) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)))
    throw CompressionError("lz4: cannot create a decompression context");
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw, LZ4F_freeDecompressionContext);
  if (size > kLz4MaxRatio * data.size())
    throw CompressionError("lz4: " + std::to_string(data.size()) + " bytes cannot hold " +
                           std::to_string(size));
  std::vector<std::uint8_t> out(size);
  std::size_t in_pos = 0, out_pos = 0, hint = 1;
  while (hint != 0 && in_pos < data.size()) {
    std::size_t in_n = data.size() - in_pos, out_n = out.size() - out_pos;
    hint = LZ4F_decompress(ctx.get(), out.data() + out_pos, &out_n, data.data() + in_pos, &in_n,
                           nullptr);
    if (LZ4F_isError(hint)) throw CompressionError(std::string("lz4: ") + LZ4F_getErrorName(hint));
    if (in_n == 0 && out_n == 0) break;  // no progress: the output is full
    in_pos += in_n, out_pos += out_n;
  }
  if (hint != 0 || out_pos != size)
    throw CompressionError("lz4: the frame gives " + std::to_string(out_pos) +
                           " bytes (complete: " + (hint == 0 ? "yes" : "no") + ") instead of " +
                           std::to_string(size));
  return out;
}

}  // namespace

std::vector<std::uint8_t> decompress(const std::string& compression,
                                     std::span<const std::uint8_t> data, std::uint64_t size) {
  if (compression.empty()) {
    if (data.size() != size)
      throw CompressionError("uncompressed chunk of " + std::to_string(data.size()) +
                             " bytes announces " + std::to_string(size));
    return {data.begin(), data.end()};
  }
  if (compression == "zstd") return zstd_decompress(data, size);
  if (compression == "lz4") return lz4_decompress(data, size);
  throw CompressionError("unknown chunk compression '" + compression +
                         "' (supported: none, zstd, lz4)");
}

std::vector<std::uint8_t> compress(const std::string& compression,
                                   std::span<const std::uint8_t> data) {
  if (compression.empty()) return {data.begin(), data.end()};
  if (compression == "zstd") {
    std::vector<std::uint8_t> out(ZSTD_compressBound(data.size()));
    const std::size_t n = ZSTD_compress(out.data(), out.size(), data.data(), data.size(), kZstdLevel);
    if (ZSTD_isError(n)) throw CompressionError(std::string("zstd: ") + ZSTD_getErrorName(n));
    out.resize(n);
    return out;
  }
  if (compression == "lz4") {
    std::vector<std::uint8_t> out(LZ4F_compressFrameBound(data.size(), nullptr));
    const std::size_t n =
        LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), nullptr);
    if (LZ4F_isError(n)) throw CompressionError(std::string("lz4: ") + LZ4F_getErrorName(n));
    out.resize(n);
    return out;
  }
  throw CompressionError("unknown chunk compression '" + compression + "'");
}

}  // namespace rownav::io::mcap
