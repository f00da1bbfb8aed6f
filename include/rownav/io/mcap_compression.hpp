#pragma once
/// @file mcap_compression.hpp The chunk compressions of MCAP: "" (none), "zstd" (a Zstandard
/// frame, libzstd) and "lz4" (an LZ4 frame, liblz4's lz4frame).
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace rownav::io::mcap {

/// Unknown compression, or data that does not decompress to the announced size.
class CompressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Decompresses `data` to exactly `size` bytes.
std::vector<std::uint8_t> decompress(const std::string& compression,
                                     std::span<const std::uint8_t> data, std::uint64_t size);

/// Compresses `data` ("", "zstd" or "lz4").
std::vector<std::uint8_t> compress(const std::string& compression,
                                   std::span<const std::uint8_t> data);

}  // namespace rownav::io::mcap
