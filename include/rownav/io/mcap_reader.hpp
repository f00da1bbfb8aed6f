#pragma once
/// @file mcap_reader.hpp Reads the messages of an MCAP file (io/mcap.hpp) in file order, straight
/// through the data section: Header, Schema, Channel, Message and Chunk records (compression "",
/// "zstd" or "lz4", CRC checked when set); the rest (indexes, attachments, metadata, statistics)
/// is skipped (Metadata records are kept: metadata()), the summary section is never needed. InputError on anything malformed: bad magic,
/// a record longer than the file (truncated), a message of an unknown channel, an unknown
/// compression, a chunk that does not decompress to its size or checksum, no Data End / Footer.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace rownav::io {

/// A channel and its schema's name and encoding (empty when it has no schema).
struct McapChannel {
  std::uint16_t id = 0;
  std::string topic, message_encoding, schema_name, schema_encoding;
};

/// Where a message is: the file offset of its chunk record (kNoChunk: a top-level message) and
/// the offset of its record in the chunk's uncompressed records (or in the file).
struct McapRef {
  static constexpr std::uint64_t kNoChunk = ~std::uint64_t{0};
  std::uint64_t chunk = kNoChunk;
  std::uint64_t offset = 0;
};

/// One message, valid during the callback.
struct McapMessage {
  const McapChannel* channel = nullptr;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0, publish_time = 0;  ///< [ns]
  std::span<const std::uint8_t> data;
  McapRef ref;
};

class McapReader {
 public:
  /// Opens `file` and checks the magic and the Header record.
  explicit McapReader(const std::filesystem::path& file);

  /// The Header's profile ("ros2" for rosbag2).
  const std::string& profile() const { return profile_; }
  /// Calls `on_message` for every message in file order.
  void read(const std::function<void(const McapMessage&)>& on_message);
  /// The data of the message at `ref` (from read()); the last chunk read is kept decompressed.
  std::vector<std::uint8_t> message_data(const McapRef& ref);
  /// Channels seen so far by id.
  const std::map<std::uint16_t, McapChannel>& channels() const { return channels_; }
  const std::filesystem::path& file() const { return file_; }
  /// Metadata records read so far: name -> key -> value.
  const std::map<std::string, std::map<std::string, std::string>>& metadata() const {
    return metadata_;
  }

 private:
  struct Record {
    std::uint8_t opcode = 0;
    std::uint64_t offset = 0;  // of the opcode in the file
    std::vector<std::uint8_t> content;
  };
  bool next_record(Record& r);  // false at the end of the file
  const std::vector<std::uint8_t>& chunk_records(std::uint64_t chunk_offset,
                                                 std::span<const std::uint8_t> content);
  void on_chunk(const Record& r, const std::function<void(const McapMessage&)>& f);
  void on_schema(std::span<const std::uint8_t> content, std::uint64_t offset);
  void on_channel(std::span<const std::uint8_t> content, std::uint64_t offset);
  void on_metadata(std::span<const std::uint8_t> content, std::uint64_t offset);
  McapMessage message(std::span<const std::uint8_t> content, std::uint64_t offset) const;

  std::filesystem::path file_;
  std::ifstream in_;
  std::uint64_t size_ = 0, pos_ = 0;
  std::string profile_;
  struct Schema {
    std::string name, encoding;
  };
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, McapChannel> channels_;
  std::map<std::string, std::map<std::string, std::string>> metadata_;
  std::uint64_t cached_chunk_ = McapRef::kNoChunk;
  std::vector<std::uint8_t> cached_records_;
};

}  // namespace rownav::io
