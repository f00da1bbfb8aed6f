// ROS 2 CDR (XCDR1) reading and writing (io/cdr.hpp).
#include "rownav/io/cdr.hpp"

#include <bit>
#include <cstring>

namespace rownav::io {

namespace {

constexpr std::size_t kEncapsulationBytes = 4;  // representation id (2) + options (2)
constexpr std::uint8_t kCdrBigEndian = 0x00;    // second byte of the representation id
constexpr std::uint8_t kCdrLittleEndian = 0x01;
constexpr std::size_t kMaxAlignment = 8;  // XCDR1 aligns 8-byte primitives to 8

}  // namespace

CdrReader::CdrReader(std::span<const std::uint8_t> message) {
  if (message.size() < kEncapsulationBytes)
    throw CdrError("CDR message shorter than its 4-byte encapsulation header");
  if (message[0] != 0 || (message[1] != kCdrBigEndian && message[1] != kCdrLittleEndian))
    throw CdrError("unsupported CDR encapsulation 0x" + std::to_string(message[0]) + "," +
                   std::to_string(message[1]) + " (expected plain CDR, big or little endian)");
  big_endian_ = message[1] == kCdrBigEndian;
  data_ = message.subspan(kEncapsulationBytes);
}

void CdrReader::align(std::size_t n) {
  const std::size_t a = std::min(n, kMaxAlignment);
  const std::size_t pad = (a - pos_ % a) % a;
  if (pad > remaining()) pos_ = data_.size();
  else pos_ += pad;
}

std::span<const std::uint8_t> CdrReader::take(std::size_t n) {
  if (n > remaining())
    throw CdrError("truncated CDR message: " + std::to_string(n) + " byte(s) needed at offset " +
                   std::to_string(pos_) + ", " + std::to_string(remaining()) + " left");
  const auto s = data_.subspan(pos_, n);
  pos_ += n;
  return s;
}

template <class U>
U CdrReader::unsigned_value() {
  align(sizeof(U));
  const auto b = take(sizeof(U));
  U v = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) {
    const std::size_t k = big_endian_ ? i : sizeof(U) - 1 - i;
    v = static_cast<U>((v << 8) | b[k]);
  }
  return v;
}

std::uint8_t CdrReader::u8() { return take(1)[0]; }
std::uint16_t CdrReader::u16() { return unsigned_value<std::uint16_t>(); }
std::uint32_t CdrReader::u32() { return unsigned_value<std::uint32_t>(); }
std::uint64_t CdrReader::u64() { return unsigned_value<std::uint64_t>(); }
float CdrReader::f32() { return std::bit_cast<float>(u32()); }
double CdrReader::f64() { return std::bit_cast<double>(u64()); }

std::string CdrReader::string() {
  const std::uint32_t n = u32();
  if (n == 0) return {};  // some writers send 0 for an empty string
  const auto b = take(n);
  if (b[n - 1] != 0) throw CdrError("CDR string without its terminating NUL");
  return std::string(reinterpret_cast<const char*>(b.data()), n - 1);
}

std::uint32_t CdrReader::sequence_length(std::size_t element_size) {
  const std::uint32_t n = u32();
  if (element_size > 0 && n > remaining() / element_size)
    throw CdrError("CDR sequence of " + std::to_string(n) + " element(s) longer than the " +
                   std::to_string(remaining()) + " byte(s) left");
  return n;
}

std::span<const std::uint8_t> CdrReader::bytes(std::size_t n) { return take(n); }

CdrWriter::CdrWriter(bool big_endian) : big_endian_(big_endian) {
  out_ = {0, big_endian ? kCdrBigEndian : kCdrLittleEndian, 0, 0};
}

void CdrWriter::align(std::size_t n) {
  const std::size_t a = std::min(n, kMaxAlignment);
  while ((out_.size() - kEncapsulationBytes) % a != 0) out_.push_back(0);
}

template <class U>
void CdrWriter::unsigned_value(U v) {
  align(sizeof(U));
  for (std::size_t i = 0; i < sizeof(U); ++i) {
    const std::size_t shift = 8 * (big_endian_ ? sizeof(U) - 1 - i : i);
    out_.push_back(static_cast<std::uint8_t>(v >> shift));
  }
}

void CdrWriter::u8(std::uint8_t v) { out_.push_back(v); }
void CdrWriter::u16(std::uint16_t v) { unsigned_value(v); }
void CdrWriter::u32(std::uint32_t v) { unsigned_value(v); }
void CdrWriter::u64(std::uint64_t v) { unsigned_value(v); }
void CdrWriter::f32(float v) { unsigned_value(std::bit_cast<std::uint32_t>(v)); }
void CdrWriter::f64(double v) { unsigned_value(std::bit_cast<std::uint64_t>(v)); }

void CdrWriter::string(const std::string& s) {
  u32(static_cast<std::uint32_t>(s.size() + 1));
  out_.insert(out_.end(), s.begin(), s.end());
  out_.push_back(0);
}

void CdrWriter::bytes(std::span<const std::uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }

}  // namespace rownav::io
