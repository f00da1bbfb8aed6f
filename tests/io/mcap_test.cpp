// The MCAP container: the writer's files read back through chunks of each compression, a file
// built byte by byte from the spec, and malformed files as one-line InputErrors.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"
#include "rownav/io/bag_recording.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/mcap.hpp"
#include "rownav/io/mcap_reader.hpp"
#include "rownav/io/mcap_writer.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

struct Read {
  std::string topic, schema;
  std::uint32_t sequence;
  std::uint64_t log_time;
  std::vector<std::uint8_t> data;
  McapRef ref;
};

std::vector<Read> read_all(McapReader& r) {
  std::vector<Read> out;
  r.read([&](const McapMessage& m) {
    out.push_back({m.channel->topic, m.channel->schema_name, m.sequence, m.log_time,
                   {m.data.begin(), m.data.end()}, m.ref});
  });
  return out;
}

std::vector<std::uint8_t> payload(std::size_t i) {
  std::vector<std::uint8_t> d(50 + i % 7);
  for (std::size_t k = 0; k < d.size(); ++k) d[k] = static_cast<std::uint8_t>(i * 31 + k);
  return d;
}

/// 40 messages on two channels, in chunks of ~500 bytes.
void write_sample(const fs::path& file, const std::string& compression) {
  McapWriterConfig c;
  c.compression = compression;
  c.chunk_bytes = 500;
  McapWriter w(file, c);
  w.write_metadata("rownav", {{"manifest", "format: x"}});
  const auto a = w.add_channel(w.add_schema("sensor_msgs/msg/Imu", "ros2msg", ""), "/imu", "cdr");
  const auto b = w.add_channel(0, "/raw", "cdr");
  for (std::size_t i = 0; i < 40; ++i) w.write(i % 3 == 0 ? b : a, 1000 * i, payload(i));
  w.close();
}

std::string slurp(const fs::path& f) { return test::read_file(f); }
void spit(const fs::path& f, const std::string& s) { std::ofstream(f, std::ios::binary) << s; }

TEST(Mcap, EveryCompressionRoundTripsThroughChunks) {
  test::TempDir dir("mcap");
  for (const std::string compression : {"", "zstd", "lz4"}) {
    const fs::path file = dir / ("s" + compression + ".mcap");
    write_sample(file, compression);
    McapReader r(file);
    EXPECT_EQ(r.profile(), "ros2");
    const auto msgs = read_all(r);
    ASSERT_EQ(msgs.size(), 40u) << compression;
    std::size_t chunks = 0;
    for (std::size_t i = 0; i < msgs.size(); ++i) {
      EXPECT_EQ(msgs[i].topic, i % 3 == 0 ? "/raw" : "/imu");
      EXPECT_EQ(msgs[i].schema, i % 3 == 0 ? "" : "sensor_msgs/msg/Imu");
      EXPECT_EQ(msgs[i].log_time, 1000 * i);
      EXPECT_EQ(msgs[i].data, payload(i)) << compression << " " << i;
      chunks += i == 0 || msgs[i].ref.chunk != msgs[i - 1].ref.chunk;
    }
    EXPECT_EQ(msgs[38].sequence, 25u);  // the 26th message on /imu, numbered from 0
    EXPECT_EQ(msgs[39].sequence, 13u);  // the 14th on /raw
    EXPECT_GT(chunks, 3u);
    // Random access: the last message, then the first (another chunk), then again.
    for (const std::size_t i : {39, 0, 1, 39})
      EXPECT_EQ(r.message_data(msgs[i].ref), payload(i)) << compression << " " << i;
    EXPECT_EQ(r.metadata().at("rownav").at("manifest"), "format: x");
  }
  EXPECT_LT(fs::file_size(dir / "szstd.mcap"), fs::file_size(dir / "s.mcap"));
}

/// Little-endian record bytes, written here straight from the spec.
struct Spec {
  std::string s;
  template <class U>
  Spec& put(U v) {
    for (std::size_t i = 0; i < sizeof(U); ++i) s.push_back(char(v >> (8 * i)));
    return *this;
  }
  Spec& str(const std::string& t) { return put(std::uint32_t(t.size())), s += t, *this; }
  Spec& record(std::uint8_t op, const Spec& content) {
    return put(op).put(std::uint64_t(content.s.size())), s += content.s, *this;
  }
};

std::string spec_file(bool footer) {
  Spec f;
  f.s = std::string(reinterpret_cast<const char*>(mcap::kMagic.data()), mcap::kMagic.size());
  f.record(mcap::header, Spec().str("ros2").str("hand"));
  f.record(mcap::schema, Spec().put(std::uint16_t(5)).str("nav_msgs/msg/Odometry").str("ros2msg").str(""));
  f.record(mcap::channel, Spec().put(std::uint16_t(9)).put(std::uint16_t(5)).str("/odom").str("cdr").put(std::uint32_t(0)));
  f.record(mcap::message, Spec().put(std::uint16_t(9)).put(std::uint32_t(4)).put(std::uint64_t(77)).put(std::uint64_t(78)).str("xyz"));
  f.record(mcap::statistics, Spec().put(std::uint64_t(1)));  // skipped
  if (!footer) return f.s;
  f.record(mcap::data_end, Spec().put(std::uint32_t(0)));
  f.record(mcap::footer, Spec().put(std::uint64_t(0)).put(std::uint64_t(0)).put(std::uint32_t(0)));
  return f.s + std::string(reinterpret_cast<const char*>(mcap::kMagic.data()), mcap::kMagic.size());
}

TEST(Mcap, ReadsATopLevelMessageOfAFileBuiltFromTheSpec) {
  test::TempDir dir("mcap");
  spit(dir / "a.mcap", spec_file(true));
  McapReader r(dir / "a.mcap");
  const auto msgs = read_all(r);
  ASSERT_EQ(msgs.size(), 1u);
  EXPECT_EQ(msgs[0].topic, "/odom");
  EXPECT_EQ(msgs[0].schema, "nav_msgs/msg/Odometry");
  EXPECT_EQ(msgs[0].sequence, 4u);
  EXPECT_EQ(msgs[0].log_time, 77u);
  EXPECT_EQ(std::string(msgs[0].data.begin(), msgs[0].data.end()), std::string("\3\0\0\0xyz", 7));
  EXPECT_EQ(r.message_data(msgs[0].ref), msgs[0].data);
}

/// Reading `bytes` throws one line containing `reason`.
void expect_error(const fs::path& file, const std::string& bytes, const std::string& reason) {
  spit(file, bytes);
  try {
    McapReader r(file);
    read_all(r);
    ADD_FAILURE() << "no error, expected: " << reason;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(reason), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind(file.string(), 0), 0u) << what;
  }
}

TEST(Mcap, MalformedFilesAreOneLineInputErrors) {
  test::TempDir dir("mcap");
  const fs::path f = dir / "bad.mcap";
  write_sample(dir / "good.mcap", "zstd");
  const std::string good = slurp(dir / "good.mcap");
  expect_error(f, "PK\3\4 not an mcap", "not an MCAP file");
  expect_error(f, spec_file(false), "no Data End or Footer");
  // Data End (13 bytes), Footer (29) and the magic (8) are the last 50 bytes: cut before them.
  for (const std::size_t cut : {std::size_t{12}, good.size() / 3, good.size() / 2, good.size() - 51})
    expect_error(f, good.substr(0, cut), "truncated");
  std::string unknown = good;
  const auto at = unknown.find("zstd");
  ASSERT_NE(at, std::string::npos);
  unknown[at + 3] = 'x';
  expect_error(f, unknown, "unknown chunk compression 'zstx'");
  std::string corrupt = good;
  corrupt[good.find("zstd") + 20] ^= 0x5A;  // inside the first compressed chunk
  expect_error(f, corrupt, "byte ");
  std::string orphan = spec_file(true);
  orphan[orphan.find("/odom") - 6] = 8;  // the channel names schema 8, which does not exist
  expect_error(f, orphan, "unknown schema 8");
}

TEST(Mcap, AChunkAnnouncingMoreThanItCanHoldIsRefusedBeforeAllocating) {
  test::TempDir dir("mcap");
  write_sample(dir / "good.mcap", "lz4");
  const std::string good = slurp(dir / "good.mcap");
  const std::size_t size_at = good.find("lz4") - 4 - 4 - 8;  // uncompressed_size, crc, length
  for (const auto& [size, reason] : {std::pair<std::uint64_t, std::string>{std::uint64_t{1} << 40, "limit"},
                                     {std::uint64_t{100} << 20, "cannot hold"}}) {
    std::string bad = good;
    for (std::size_t i = 0; i < 8; ++i) bad[size_at + i] = char(size >> (8 * i));
    expect_error(dir / "bad.mcap", bad, reason);
  }
}

TEST(Mcap, AFileCutAfterItsDataEndStillReadsEveryMessage) {
  test::TempDir dir("mcap");
  write_sample(dir / "good.mcap", "lz4");
  const std::string good = slurp(dir / "good.mcap");
  spit(dir / "cut.mcap", good.substr(0, good.size() - 30));  // inside the Footer
  McapReader r(dir / "cut.mcap");
  EXPECT_EQ(read_all(r).size(), 40u);
}

TEST(Mcap, WriterRefusesBadConfig) {
  McapWriterConfig c;
  c.compression = "bz2";
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c.compression = "lz4";
  c.chunk_bytes = 0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(BagWriters, McapIsAlwaysWritableABagOnlyWithAWriterAndOtherFormatsNever) {
  EXPECT_NO_THROW(check_bag_writable("run.mcap"));
  EXPECT_NO_THROW(check_bag_writable("RUN.MCAP"));
  register_bag_writer(".bag", nullptr);  // as in a build without ROS
  try {
    check_bag_writable("run.bag");
    ADD_FAILURE() << "a .bag without a writer was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("librosbag"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_bag_writable("run.db3"), InputError);
  int written = 0;
  register_bag_writer(".bag", [&](const Recording&, const fs::path&) { ++written; });
  EXPECT_NO_THROW(check_bag_writable("run.bag"));
  write_bag_recording(Recording{}, "staging.tmp", "run.bag");
  EXPECT_EQ(written, 1);
  // The writer's error names the user's file, not the staging name.
  register_bag_writer(".bag", [](const Recording&, const fs::path& f) {
    throw InputError(f.string(), "", "disk full");
  });
  try {
    write_bag_recording(Recording{}, ".run.bag.partial", "run.bag");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "run.bag: disk full");
  }
  register_bag_writer(".bag", nullptr);
}

}  // namespace
}  // namespace rownav::io
