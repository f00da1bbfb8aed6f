#pragma once
/// @file cdr.hpp ROS 2 CDR (XCDR1, "plain CDR") serialisation, as rmw's Fast-CDR writes it: a
/// 4-byte encapsulation header (0x00 0x00 big-endian, 0x00 0x01 little-endian, 2 option bytes),
/// then every primitive aligned to its own size (at most 8) relative to the byte after that
/// header; a string is a uint32 length counting its NUL, the bytes and the NUL; a sequence a
/// uint32 element count, then the elements.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace rownav::io {

/// A malformed or truncated CDR message (what() is one line, without the file name: the bag
/// reader adds the file and the message).
class CdrError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads one CDR message. Never reads past the message; throws CdrError instead.
class CdrReader {
 public:
  /// Checks the encapsulation header (CDR_BE or CDR_LE; anything else is refused).
  explicit CdrReader(std::span<const std::uint8_t> message);

  std::uint8_t u8();
  std::uint16_t u16();
  std::uint32_t u32();
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::uint64_t u64();
  float f32();
  double f64();
  bool boolean() { return u8() != 0; }
  std::string string();
  /// A sequence length that must fit in the rest of the message at `element_size` bytes each.
  std::uint32_t sequence_length(std::size_t element_size);
  /// `n` raw bytes (uint8[] content), no alignment.
  std::span<const std::uint8_t> bytes(std::size_t n);

  bool big_endian() const { return big_endian_; }
  std::size_t remaining() const { return data_.size() - pos_; }

 private:
  void align(std::size_t n);
  std::span<const std::uint8_t> take(std::size_t n);
  template <class U>
  U unsigned_value();

  std::span<const std::uint8_t> data_;  // after the encapsulation header
  std::size_t pos_ = 0;
  bool big_endian_ = false;
};

/// Writes one CDR message (little-endian by default; big-endian for tests of the readers).
class CdrWriter {
 public:
  explicit CdrWriter(bool big_endian = false);

  void u8(std::uint8_t v);
  void u16(std::uint16_t v);
  void u32(std::uint32_t v);
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void u64(std::uint64_t v);
  void f32(float v);
  void f64(double v);
  void boolean(bool v) { u8(v ? 1 : 0); }
  void string(const std::string& s);
  void bytes(std::span<const std::uint8_t> b);

  /// The message, encapsulation header first.
  const std::vector<std::uint8_t>& data() const { return out_; }

 private:
  void align(std::size_t n);
  template <class U>
  void unsigned_value(U v);

  std::vector<std::uint8_t> out_;
  bool big_endian_;
};

}  // namespace rownav::io
