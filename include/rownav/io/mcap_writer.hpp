#pragma once
/// @file mcap_writer.hpp A small MCAP writer (io/mcap.hpp): Header (profile "ros2"), Schema and
/// Channel records at the top level, messages in chunks (uncompressed, zstd or lz4, CRC set),
/// Data End and a Footer without a summary section (readers that need an index rebuild it, e.g.
/// `mcap recover`). Writes to the given path directly; the callers stage it (io/safe_output.hpp).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace rownav::io {

struct McapWriterConfig {
  std::string compression = "zstd";        ///< chunk compression: "" (none), "zstd" or "lz4"
  std::uint64_t chunk_bytes = 1u << 20;    ///< [bytes] uncompressed records a chunk holds (>= 1)

  /// std::invalid_argument naming the field.
  void validate() const;
};

class McapWriter {
 public:
  /// Opens `file` and writes the magic and the Header (std::runtime_error when it cannot).
  McapWriter(const std::filesystem::path& file, McapWriterConfig config = {});
  /// Closes the file if close() was not called (errors then are lost: call close()).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// A schema (`encoding` "ros2msg" for ROS 2 types; `data` its definition text); returns its id.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           const std::string& data);
  /// A channel on `schema` (0: none), `message_encoding` "cdr" for ROS 2; returns its id.
  std::uint16_t add_channel(std::uint16_t schema, const std::string& topic,
                            const std::string& message_encoding);
  /// One message; `log_time` [ns] is also the publish time.
  void write(std::uint16_t channel, std::uint64_t log_time, std::span<const std::uint8_t> data);
  /// A Metadata record (name + string map), at the top level.
  void write_metadata(const std::string& name,
                      const std::vector<std::pair<std::string, std::string>>& values);
  /// Flushes the last chunk, writes Data End, Footer and the closing magic.
  void close();

 private:
  void flush_chunk();
  void record(std::vector<std::uint8_t>& out, std::uint8_t opcode,
              const std::vector<std::uint8_t>& content);

  std::filesystem::path file_;
  McapWriterConfig config_;
  std::ofstream out_;
  std::vector<std::uint8_t> chunk_;  // uncompressed records of the open chunk
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::uint16_t schemas_ = 0, channels_ = 0;
  std::vector<std::uint32_t> sequence_;  // next sequence number by channel
  bool closed_ = false;
};

}  // namespace rownav::io
