// MCAP constants and the chunk checksum (io/mcap.hpp).
#include "rownav/io/mcap.hpp"

namespace rownav::io::mcap {

namespace {

constexpr std::uint32_t kCrcPolynomial = 0xEDB88320u;  // CRC-32 ISO-HDLC, reflected
constexpr int kBitsPerByte = 8;
constexpr std::size_t kTableSize = 256;

struct CrcTable {
  std::uint32_t v[kTableSize];
  constexpr CrcTable() : v() {
    for (std::uint32_t i = 0; i < kTableSize; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < kBitsPerByte; ++k) c = (c & 1u) ? kCrcPolynomial ^ (c >> 1) : c >> 1;
      v[i] = c;
    }
  }
};

constexpr CrcTable kTable;

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = kTable.v[(crc ^ data[i]) & 0xFFu] ^ (crc >> kBitsPerByte);
  return ~crc;
}

}  // namespace rownav::io::mcap
