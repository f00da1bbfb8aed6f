// Sequential MCAP reading through chunks (io/mcap_reader.hpp).
#include "rownav/io/mcap_reader.hpp"

#include <algorithm>

#include "rownav/io/input_error.hpp"
#include "rownav/io/mcap.hpp"
#include "rownav/io/mcap_compression.hpp"

namespace rownav::io {

namespace {

/// [bytes] largest chunk decompressed: rosbag2 and the MCAP writers close a chunk at a few MiB
/// (one message larger than that gets a chunk of its own); a corrupt size field must not
/// allocate the machine's memory (the fuzz targets run in 512 MB).
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{256} << 20;

/// Little-endian fields of one record's content; InputError at the record's offset.
class Fields {
 public:
  Fields(std::span<const std::uint8_t> d, const std::filesystem::path& file, std::uint64_t offset,
         const char* what)
      : d_(d), file_(file), offset_(offset), what_(what) {}

  template <class U>
  U get() {
    const auto b = take(sizeof(U));
    U v = 0;
    for (std::size_t i = sizeof(U); i-- > 0;) v = static_cast<U>((v << 8) | b[i]);
    return v;
  }
  std::string string() {
    const auto b = take(get<std::uint32_t>());
    return {reinterpret_cast<const char*>(b.data()), b.size()};
  }
  std::span<const std::uint8_t> take(std::uint64_t n) {
    if (n > d_.size() - pos_)
      throw InputError(file_.string(), "byte " + std::to_string(offset_),
                       std::string(what_) + " record shorter than its fields");
    const auto s = d_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  std::span<const std::uint8_t> rest() { return take(d_.size() - pos_); }
  bool rest_empty() const { return pos_ == d_.size(); }

 private:
  std::span<const std::uint8_t> d_;
  std::size_t pos_ = 0;
  const std::filesystem::path& file_;
  std::uint64_t offset_;
  const char* what_;
};

}  // namespace

McapReader::McapReader(const std::filesystem::path& file) : file_(file), in_(file, std::ios::binary) {
  if (!in_) throw InputError(file.string(), "", "cannot open");
  std::error_code ec;
  size_ = std::filesystem::file_size(file, ec);
  std::array<std::uint8_t, mcap::kMagic.size()> magic{};
  in_.read(reinterpret_cast<char*>(magic.data()), magic.size());
  if (ec || !in_ || magic != mcap::kMagic)
    throw InputError(file.string(), "byte 0", "not an MCAP file (no \\x89MCAP0\\r\\n magic)");
  pos_ = magic.size();
  Record r;
  if (!next_record(r) || r.opcode != mcap::header)
    throw InputError(file.string(), "byte " + std::to_string(pos_),
                     "MCAP file without its Header record");
  Fields f(r.content, file_, r.offset, "Header");
  profile_ = f.string();
}

bool McapReader::next_record(Record& r) {
  if (pos_ == size_) return false;
  r.offset = pos_;
  if (size_ - pos_ < mcap::kRecordPrefix)
    throw InputError(file_.string(), "byte " + std::to_string(pos_), "truncated MCAP record");
  std::uint8_t prefix[mcap::kRecordPrefix];
  in_.seekg(static_cast<std::streamoff>(pos_));
  in_.read(reinterpret_cast<char*>(prefix), sizeof(prefix));
  Fields f({prefix, sizeof(prefix)}, file_, pos_, "");
  r.opcode = f.get<std::uint8_t>();
  const auto length = f.get<std::uint64_t>();
  if (!in_ || length > size_ - pos_ - mcap::kRecordPrefix)
    throw InputError(file_.string(), "byte " + std::to_string(pos_),
                     "truncated MCAP file: a record of " + std::to_string(length) +
                         " bytes, " + std::to_string(size_ - pos_ - mcap::kRecordPrefix) +
                         " left");
  r.content.resize(length);
  in_.read(reinterpret_cast<char*>(r.content.data()), static_cast<std::streamsize>(length));
  if (!in_) throw InputError(file_.string(), "byte " + std::to_string(pos_), "read error");
  pos_ += mcap::kRecordPrefix + length;
  return true;
}

void McapReader::read(const std::function<void(const McapMessage&)>& on_message) {
  Record r;
  while (next_record(r)) {
    const std::span<const std::uint8_t> c = r.content;
    switch (r.opcode) {
      case mcap::schema: on_schema(c, r.offset); break;
      case mcap::channel: on_channel(c, r.offset); break;
      case mcap::message: {
        McapMessage m = message(c, r.offset);
        m.ref = {McapRef::kNoChunk, r.offset};
        on_message(m);
        break;
      }
      case mcap::chunk: on_chunk(r, on_message); break;
      case mcap::metadata: on_metadata(c, r.offset); break;
      case mcap::header:
        throw InputError(file_.string(), "byte " + std::to_string(r.offset), "a second Header");
      case mcap::data_end:
      case mcap::footer: return;  // the summary section repeats what was read
      default: break;  // indexes, attachments, metadata, statistics, user records
    }
  }
  throw InputError(file_.string(), "byte " + std::to_string(pos_),
                   "truncated MCAP file: no Data End or Footer record");
}

const std::vector<std::uint8_t>& McapReader::chunk_records(std::uint64_t chunk_offset,
                                                           std::span<const std::uint8_t> content) {
  if (cached_chunk_ == chunk_offset) return cached_records_;
  Fields f(content, file_, chunk_offset, "Chunk");
  f.get<std::uint64_t>(), f.get<std::uint64_t>();  // message start / end time
  const auto size = f.get<std::uint64_t>();
  const auto crc = f.get<std::uint32_t>();
  const std::string compression = f.string();
  const auto records = f.take(f.get<std::uint64_t>());
  const std::string at = "byte " + std::to_string(chunk_offset);
  if (size > kMaxChunkBytes)
    throw InputError(file_.string(), at, "chunk of " + std::to_string(size) + " bytes (limit " +
                                             std::to_string(kMaxChunkBytes) + ")");
  cached_chunk_ = McapRef::kNoChunk;
  try {
    cached_records_ = mcap::decompress(compression, records, size);
  } catch (const mcap::CompressionError& e) {
    throw InputError(file_.string(), at, e.what());
  }
  if (crc != 0 && mcap::crc32(cached_records_.data(), cached_records_.size()) != crc)
    throw InputError(file_.string(), at, "chunk CRC mismatch (corrupt data)");
  cached_chunk_ = chunk_offset;
  return cached_records_;
}

void McapReader::on_chunk(const Record& r, const std::function<void(const McapMessage&)>& f) {
  const std::vector<std::uint8_t>& records = chunk_records(r.offset, r.content);
  const std::span<const std::uint8_t> all = records;
  std::uint64_t pos = 0;
  while (pos < all.size()) {
    const std::string at = "chunk at byte " + std::to_string(r.offset) + ", record at " +
                           std::to_string(pos);
    if (all.size() - pos < mcap::kRecordPrefix)
      throw InputError(file_.string(), at, "truncated record in a chunk");
    Fields p(all.subspan(pos, mcap::kRecordPrefix), file_, r.offset, "Chunk");
    const auto op = p.get<std::uint8_t>();
    const auto length = p.get<std::uint64_t>();
    if (length > all.size() - pos - mcap::kRecordPrefix)
      throw InputError(file_.string(), at, "record longer than its chunk");
    const auto c = all.subspan(pos + mcap::kRecordPrefix, length);
    if (op == mcap::schema) on_schema(c, r.offset);
    else if (op == mcap::channel) on_channel(c, r.offset);
    else if (op == mcap::message) {
      McapMessage m = message(c, r.offset);
      m.ref = {r.offset, pos};
      f(m);
    }
    pos += mcap::kRecordPrefix + length;
  }
}

void McapReader::on_schema(std::span<const std::uint8_t> content, std::uint64_t offset) {
  Fields f(content, file_, offset, "Schema");
  const auto id = f.get<std::uint16_t>();
  Schema s;
  s.name = f.string();
  s.encoding = f.string();
  if (id == 0) throw InputError(file_.string(), "byte " + std::to_string(offset), "schema id 0");
  schemas_[id] = std::move(s);
}

void McapReader::on_channel(std::span<const std::uint8_t> content, std::uint64_t offset) {
  Fields f(content, file_, offset, "Channel");
  McapChannel c;
  c.id = f.get<std::uint16_t>();
  const auto schema = f.get<std::uint16_t>();
  c.topic = f.string();
  c.message_encoding = f.string();
  if (schema != 0) {
    const auto it = schemas_.find(schema);
    if (it == schemas_.end())
      throw InputError(file_.string(), "byte " + std::to_string(offset),
                       "channel '" + c.topic + "' names unknown schema " + std::to_string(schema));
    c.schema_name = it->second.name;
    c.schema_encoding = it->second.encoding;
  }
  channels_[c.id] = std::move(c);
}

void McapReader::on_metadata(std::span<const std::uint8_t> content, std::uint64_t offset) {
  Fields f(content, file_, offset, "Metadata");
  auto& values = metadata_[f.string()];
  Fields map(f.take(f.get<std::uint32_t>()), file_, offset, "Metadata");
  while (!map.rest_empty()) {
    std::string key = map.string();
    values[std::move(key)] = map.string();
  }
}

McapMessage McapReader::message(std::span<const std::uint8_t> content, std::uint64_t offset) const {
  Fields f(content, file_, offset, "Message");
  McapMessage m;
  const auto channel = f.get<std::uint16_t>();
  m.sequence = f.get<std::uint32_t>();
  m.log_time = f.get<std::uint64_t>();
  m.publish_time = f.get<std::uint64_t>();
  m.data = f.rest();
  const auto it = channels_.find(channel);
  if (it == channels_.end())
    throw InputError(file_.string(), "byte " + std::to_string(offset),
                     "message on unknown channel " + std::to_string(channel));
  m.channel = &it->second;
  return m;
}

std::vector<std::uint8_t> McapReader::message_data(const McapRef& ref) {
  if (ref.chunk == McapRef::kNoChunk) {
    pos_ = ref.offset;
    Record r;
    if (!next_record(r) || r.opcode != mcap::message)
      throw InputError(file_.string(), "byte " + std::to_string(ref.offset), "not a message");
    const auto d = message(r.content, r.offset).data;
    return {d.begin(), d.end()};
  }
  pos_ = ref.chunk;
  Record r;
  if (cached_chunk_ != ref.chunk && (!next_record(r) || r.opcode != mcap::chunk))
    throw InputError(file_.string(), "byte " + std::to_string(ref.chunk), "not a chunk");
  const std::span<const std::uint8_t> all = chunk_records(ref.chunk, r.content);
  if (ref.offset + mcap::kRecordPrefix > all.size())
    throw InputError(file_.string(), "byte " + std::to_string(ref.chunk), "no such message");
  Fields p(all.subspan(ref.offset, mcap::kRecordPrefix), file_, ref.chunk, "Chunk");
  p.get<std::uint8_t>();
  const auto length = std::min<std::uint64_t>(p.get<std::uint64_t>(),
                                              all.size() - ref.offset - mcap::kRecordPrefix);
  const auto d = message(all.subspan(ref.offset + mcap::kRecordPrefix, length), ref.chunk).data;
  return {d.begin(), d.end()};
}

}  // namespace rownav::io
