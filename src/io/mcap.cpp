// MCAP constants and the chunk checksum (io/mcap.hpp).
#include "rownav/io/mcap.hpp"

#include <zlib.h>

#include <algorithm>
#include <limits>

namespace rownav::io::mcap {

std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc) {
  // zlib's CRC-32 is MCAP's (ISO-HDLC); its braided implementation is ~10x a byte table.
  uLong c = crc;
  constexpr std::size_t kMaxBlock = std::numeric_limits<uInt>::max();
  while (n > 0) {
    const std::size_t k = std::min(n, kMaxBlock);
    c = ::crc32(c, data, static_cast<uInt>(k));
    data += k, n -= k;
  }
  return static_cast<std::uint32_t>(c);
}

}  // namespace rownav::io::mcap
