// Little-endian binary encoding, whatever the host's byte order: the PLY
// writer and checkpoint.bin, which must read back identically on any machine.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace sablier {

// IEEE floats and two's-complement integers in the host's order, which the
// bulk copies below rely on (every host we build on is little-endian).
inline constexpr bool kLittleEndianHost = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

// Appends integers and IEEE floats, least significant byte first.
class ByteWriter {
 public:
  ByteWriter() = default;
  // Appends to `out` instead of a string of its own (a buffer kept between
  // writes keeps its storage).
  explicit ByteWriter(std::string* out) : data_(*out) {}
  ByteWriter(const ByteWriter&) = delete;
  ByteWriter& operator=(const ByteWriter&) = delete;

  template <class T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>, "numbers only");
    using U = std::conditional_t<sizeof(T) == 8, std::uint64_t,
                                 std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint8_t>>;
    static_assert(sizeof(T) == sizeof(U), "1, 4 or 8 bytes");
    U bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (std::size_t i = 0; i < sizeof bits; ++i)
      data_ += static_cast<char>(static_cast<unsigned char>(bits >> (8 * i)));
  }
  // A whole array, as put() would write each value: on a little-endian host
  // its bytes are already those, and are copied in one go (a checkpoint of
  // 69,120 grains in 3D, 16.5 MB: 27 ms byte by byte).
  template <class T>
  void put_all(const std::vector<T>& values) {
    if constexpr (kLittleEndianHost) {
      data_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    } else {
      for (const T x : values) put(x);
    }
  }
  void put_bytes(const std::string& s) { data_ += s; }
  void reserve(std::size_t bytes) { data_.reserve(bytes); }
  std::string& data() { return data_; }

 private:
  std::string own_;
  std::string& data_ = own_;
};

// Reads what ByteWriter wrote. `ok()` turns false, for good, at the first
// read past the end (the value read is then 0).
class ByteReader {
 public:
  ByteReader(const std::string& data, std::size_t pos = 0) : data_(data), pos_(pos) {}

  template <class T>
  T get() {
    using U = std::conditional_t<sizeof(T) == 8, std::uint64_t,
                                 std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint8_t>>;
    U bits = 0;
    if (pos_ + sizeof bits > data_.size()) {
      ok_ = false;
      pos_ = data_.size();
    } else {
      for (std::size_t i = 0; i < sizeof bits; ++i)
        bits |= static_cast<U>(static_cast<unsigned char>(data_[pos_ + i])) << (8 * i);
      pos_ += sizeof bits;
    }
    T value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  // Fills `values` (sized by the caller) as get() would one by one.
  template <class T>
  void get_all(std::vector<T>& values) {
    if constexpr (kLittleEndianHost) {
      const std::size_t bytes = values.size() * sizeof(T);
      if (pos_ + bytes > data_.size()) {
        for (T& x : values) x = get<T>();  // zeros past the end, ok() false
        return;
      }
      std::memcpy(values.data(), data_.data() + pos_, bytes);
      pos_ += bytes;
    } else {
      for (T& x : values) x = get<T>();
    }
  }
  bool ok() const { return ok_; }
  std::size_t pos() const { return pos_; }

 private:
  const std::string& data_;
  std::size_t pos_;
  bool ok_ = true;
};

}  // namespace sablier
