// A small MCAP writer: top-level schemas / channels, messages in compressed chunks
// (io/mcap_writer.hpp).
#include "rownav/io/mcap_writer.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "rownav/io/mcap.hpp"
#include "rownav/io/mcap_compression.hpp"

namespace rownav::io {

namespace {

/// Appends little-endian fields.
struct Bytes {
  std::vector<std::uint8_t> v;
  template <class U>
  Bytes& put(U x) {
    for (std::size_t i = 0; i < sizeof(U); ++i) v.push_back(static_cast<std::uint8_t>(x >> (8 * i)));
    return *this;
  }
  Bytes& string(const std::string& s) {
    put(static_cast<std::uint32_t>(s.size()));
    v.insert(v.end(), s.begin(), s.end());
    return *this;
  }
  Bytes& raw(std::span<const std::uint8_t> b) {
    v.insert(v.end(), b.begin(), b.end());
    return *this;
  }
};

}  // namespace

void McapWriterConfig::validate() const {
  if (compression != "" && compression != "zstd" && compression != "lz4")
    throw std::invalid_argument("compression: must be '', 'zstd' or 'lz4' (got '" + compression +
                                "')");
  if (chunk_bytes < 1) throw std::invalid_argument("chunk_bytes: must be >= 1");
}

McapWriter::McapWriter(const std::filesystem::path& file, McapWriterConfig config)
    : file_(file), config_(std::move(config)) {
  config_.validate();
  out_.open(file, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error(file.string() + ": cannot write");
  std::vector<std::uint8_t> head(mcap::kMagic.begin(), mcap::kMagic.end());
  record(head, mcap::header, Bytes().string("ros2").string("rownav").v);
  out_.write(reinterpret_cast<const char*>(head.data()), static_cast<std::streamsize>(head.size()));
}

McapWriter::~McapWriter() {
  if (closed_) return;
  try {
    close();
  } catch (...) {  // a destructor does not throw; close() reports errors
  }
}

void McapWriter::record(std::vector<std::uint8_t>& out, std::uint8_t opcode,
                        const std::vector<std::uint8_t>& content) {
  Bytes b;
  b.put(opcode).put(static_cast<std::uint64_t>(content.size())).raw(content);
  out.insert(out.end(), b.v.begin(), b.v.end());
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                     const std::string& data) {
  if (schemas_ == std::numeric_limits<std::uint16_t>::max())
    throw std::runtime_error("mcap: too many schemas");
  const std::uint16_t id = ++schemas_;  // 0 means "no schema"
  Bytes b;
  b.put(id).string(name).string(encoding).string(data);
  std::vector<std::uint8_t> r;
  record(r, mcap::schema, b.v);
  out_.write(reinterpret_cast<const char*>(r.data()), static_cast<std::streamsize>(r.size()));
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema, const std::string& topic,
                                      const std::string& message_encoding) {
  if (schema > schemas_) throw std::invalid_argument("mcap: unknown schema " + std::to_string(schema));
  const std::uint16_t id = channels_++;
  Bytes b;
  b.put(id).put(schema).string(topic).string(message_encoding).put(std::uint32_t{0});  // metadata
  std::vector<std::uint8_t> r;
  record(r, mcap::channel, b.v);
  out_.write(reinterpret_cast<const char*>(r.data()), static_cast<std::streamsize>(r.size()));
  sequence_.push_back(0);
  return id;
}

void McapWriter::write_metadata(const std::string& name,
                                const std::vector<std::pair<std::string, std::string>>& values) {
  Bytes map;
  for (const auto& [k, v] : values) map.string(k).string(v);
  Bytes b;
  b.string(name).put(static_cast<std::uint32_t>(map.v.size())).raw(map.v);
  std::vector<std::uint8_t> r;
  record(r, mcap::metadata, b.v);
  out_.write(reinterpret_cast<const char*>(r.data()), static_cast<std::streamsize>(r.size()));
}

void McapWriter::write(std::uint16_t channel, std::uint64_t log_time,
                       std::span<const std::uint8_t> data) {
  if (channel >= channels_)
    throw std::invalid_argument("mcap: unknown channel " + std::to_string(channel));
  if (chunk_.empty()) chunk_start_ = chunk_end_ = log_time;
  chunk_start_ = std::min(chunk_start_, log_time);
  chunk_end_ = std::max(chunk_end_, log_time);
  Bytes b;
  b.put(channel).put(sequence_[channel]++).put(log_time).put(log_time).raw(data);
  record(chunk_, mcap::message, b.v);
  if (chunk_.size() >= config_.chunk_bytes) flush_chunk();
}

void McapWriter::flush_chunk() {
  if (chunk_.empty()) return;
  const std::vector<std::uint8_t> packed = mcap::compress(config_.compression, chunk_);
  Bytes b;
  b.put(chunk_start_).put(chunk_end_).put(static_cast<std::uint64_t>(chunk_.size()));
  b.put(mcap::crc32(chunk_.data(), chunk_.size())).string(config_.compression);
  b.put(static_cast<std::uint64_t>(packed.size())).raw(packed);
  std::vector<std::uint8_t> r;
  record(r, mcap::chunk, b.v);
  out_.write(reinterpret_cast<const char*>(r.data()), static_cast<std::streamsize>(r.size()));
  chunk_.clear();
}

void McapWriter::close() {
  if (closed_) return;
  closed_ = true;
  flush_chunk();
  std::vector<std::uint8_t> tail;
  record(tail, mcap::data_end, Bytes().put(std::uint32_t{0}).v);  // no data section CRC
  // No summary section: summary_start = summary_offset_start = 0, summary_crc = 0.
  record(tail, mcap::footer,
         Bytes().put(std::uint64_t{0}).put(std::uint64_t{0}).put(std::uint32_t{0}).v);
  tail.insert(tail.end(), mcap::kMagic.begin(), mcap::kMagic.end());
  out_.write(reinterpret_cast<const char*>(tail.data()), static_cast<std::streamsize>(tail.size()));
  out_.close();
  if (!out_) throw std::runtime_error(file_.string() + ": cannot write");
}

}  // namespace rownav::io
