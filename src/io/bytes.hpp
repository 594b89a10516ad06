// Little-endian binary encoding, whatever the host's byte order: the PLY
// writer and checkpoint.bin, which must read back identically on any machine.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

namespace sablier {

// Appends integers and IEEE floats, least significant byte first.
class ByteWriter {
 public:
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
  void put_bytes(const std::string& s) { data_ += s; }
  void reserve(std::size_t bytes) { data_.reserve(bytes); }
  std::string& data() { return data_; }

 private:
  std::string data_;
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
  bool ok() const { return ok_; }
  std::size_t pos() const { return pos_; }

 private:
  const std::string& data_;
  std::size_t pos_;
  bool ok_ = true;
};

}  // namespace sablier
