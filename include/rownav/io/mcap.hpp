#pragma once
/// @file mcap.hpp The MCAP container (https://mcap.dev/spec, version 0), as rownav reads and
/// writes it: the magic `\x89MCAP0\r\n`, then records (uint8 opcode, uint64 content length,
/// content; little-endian; strings and byte arrays prefixed by a uint32 length, a chunk's
/// records by a uint64 one), then the magic again.
#include <array>
#include <cstdint>

namespace rownav::io::mcap {

inline constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr std::size_t kRecordPrefix = 9;  ///< opcode (1) + content length (8)

/// Record opcodes of the spec.
enum Opcode : std::uint8_t {
  header = 0x01,
  footer = 0x02,
  schema = 0x03,
  channel = 0x04,
  message = 0x05,
  chunk = 0x06,
  message_index = 0x07,
  chunk_index = 0x08,
  attachment = 0x09,
  attachment_index = 0x0A,
  statistics = 0x0B,
  metadata = 0x0C,
  metadata_index = 0x0D,
  summary_offset = 0x0E,
  data_end = 0x0F,
};

/// CRC-32 (ISO-HDLC, zlib's crc32) of `n` bytes, continuing from `crc` (0 to start): the
/// checksum of a chunk's uncompressed records.
std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0);

}  // namespace rownav::io::mcap
