// The parts of VTK XML files (.vtp, .vti) that every writer and reader here
// shares: the appended-data section, raw or zlib-compressed in VTK's block
// layout, the DataArray tags that point into it, and a reader that decodes
// every array of such a file back to doubles.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sablier {

// How the appended arrays are stored. Zlib is what VTK's
// vtkZLibDataCompressor reads: per array a UInt64 header (number of blocks,
// uncompressed block size, uncompressed size of a partial last block or 0,
// compressed size of each block) followed by the blocks, each compressed on
// its own with zlib.
enum class VtkCompression { None, Zlib };

// Uncompressed bytes per zlib block: large enough for a good ratio, small
// enough that blocks compress in parallel on big frames.
constexpr std::size_t kVtkZlibBlockBytes = std::size_t(1) << 16;

// The appended-data section being built: each array is added once and
// referred to by the byte offset `add` returns.
class VtkAppended {
 public:
  explicit VtkAppended(VtkCompression compression) : compression_(compression) {}

  template <class T>
  std::size_t add(const std::vector<T>& values) {
    return add_bytes(values.data(), values.size() * sizeof(T));
  }
  std::size_t add_bytes(const void* data, std::size_t bytes);
  // An array of `count` values of T, value i being at(i): appended in
  // chunks when the data is raw (no temporary copy of the whole array),
  // through a buffer when it is compressed.
  template <class T, class At>
  std::size_t add_generated(std::size_t count, At at) {
    if (compression_ != VtkCompression::None) {
      std::vector<T> values(count);
      for (std::size_t i = 0; i < count; ++i) values[i] = at(i);
      return add(values);
    }
    const std::size_t offset = data_.size();
    append_u64(count * sizeof(T));  // the raw array's header: its bytes
    constexpr std::size_t kChunk = 512;
    T chunk[kChunk];
    for (std::size_t i = 0; i < count; i += kChunk) {
      const std::size_t k = std::min(kChunk, count - i);
      for (std::size_t j = 0; j < k; ++j) chunk[j] = at(i + j);
      data_.append(reinterpret_cast<const char*>(chunk), k * sizeof(T));
    }
    return offset;
  }
  // Room for `bytes` more of appended data (raw arrays: the values' bytes
  // and 8 per array), so that a large frame grows its buffer once.
  void reserve(std::size_t bytes) { data_.reserve(data_.size() + bytes); }
  VtkCompression compression() const { return compression_; }
  const std::string& data() const { return data_; }

 private:
  // One UInt64 of a header (a raw array's size, the zlib blocks' counts and
  // sizes), in the host's order: little-endian, as the file says.
  void append_u64(std::uint64_t v) { data_.append(reinterpret_cast<const char*>(&v), sizeof v); }

  VtkCompression compression_;
  std::string data_;
};

// <DataArray type=... Name=... NumberOfComponents=... format="appended" offset=.../>
std::string vtk_array_tag(const char* type, const std::string& name, int components,
                          std::size_t offset);
// FieldData arrays also need their tuple count: readers size them by it.
std::string vtk_field_tag(const char* type, const std::string& name, std::size_t tuples,
                          std::size_t offset);
// The whole file: the XML declaration, the opening VTKFile tag of a file of
// `type` (PolyData, ImageData) naming the compressor if there is one, `xml`
// (the dataset's element), the appended-data section and the closing tags, built
// in one buffer of the final size.
std::string vtk_file(const char* type, const std::string& xml, const VtkAppended& appended);

// One array read back: its VTK type name, components and values.
struct VtkArray {
  std::string type;
  int components = 1;
  std::vector<double> values;
};

// Every DataArray of a VTK XML file with raw appended data (compressed with
// vtkZLibDataCompressor or not, header_type UInt64), by Name. Reads Float64,
// Float32, Int64, Int32 and UInt8. Throws IoError naming `source`.
std::map<std::string, VtkArray> read_vtk_arrays(const std::string& contents,
                                                const std::string& source);
// The value of attribute `key` in an XML tag's text, or "" if absent.
std::string xml_attribute(const std::string& tag, const std::string& key);

}  // namespace sablier
