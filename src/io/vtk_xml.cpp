// VTK XML appended data: raw or compressed with zlib in the block layout of
// vtkZLibDataCompressor (header_type UInt64), and a reader for both.
#include "io/vtk_xml.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>

#include "io/writers.hpp"

namespace sablier {
namespace {

// zlib level: particle data compresses barely better at higher levels (a
// collapse2d frame, 64 KiB blocks: level 1 keeps 48.2% at ~100 MB/s, level 6
// 46.9% at ~55 MB/s), and frames are written inside the time loop.
constexpr int kZlibLevel = 1;

// Each block is compressed on its own, so blocks compress in parallel; zlib's
// output depends only on the input and the level, so files stay
// bit-identical whatever the thread count.
std::vector<std::string> compress_blocks(const char* data, std::size_t bytes) {
  const auto blocks =
      static_cast<std::int64_t>((bytes + kVtkZlibBlockBytes - 1) / kVtkZlibBlockBytes);
  std::vector<std::string> out(blocks);
  int failures = 0;
#pragma omp parallel for schedule(dynamic) reduction(+ : failures) if (blocks > 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::size_t start = b * kVtkZlibBlockBytes;
    const uLong len = static_cast<uLong>(std::min(kVtkZlibBlockBytes, bytes - start));
    uLongf out_len = compressBound(len);
    out[b].resize(out_len);
    if (compress2(reinterpret_cast<Bytef*>(out[b].data()), &out_len,
                  reinterpret_cast<const Bytef*>(data + start), len, kZlibLevel) != Z_OK)
      ++failures;
    out[b].resize(out_len);
  }
  if (failures) throw IoError("zlib: compression failed (out of memory?)");
  return out;
}

// Bounds-checked reads of the appended section.
class AppendedReader {
 public:
  AppendedReader(const std::string& s, std::size_t base, const std::string& source)
      : s_(s), base_(base), source_(source) {}

  IoError fail(const std::string& why) const { return IoError(source_ + ": " + why); }

  std::uint64_t u64(std::size_t at) const {
    check(at, 8);
    std::uint64_t v;
    std::memcpy(&v, s_.data() + base_ + at, 8);
    return v;
  }
  const char* bytes(std::size_t at, std::uint64_t n) const {
    check(at, n);
    return s_.data() + base_ + at;
  }

  // A raw array: its byte count, then the bytes.
  std::string raw(std::size_t offset) const {
    const std::uint64_t n = u64(offset);
    return std::string(bytes(offset + 8, n), n);
  }

  // A compressed array: the header, then the blocks, each inflated to its
  // announced size.
  std::string inflate(std::size_t offset) const {
    const std::uint64_t blocks = u64(offset), block_size = u64(offset + 8),
                        last_size = u64(offset + 16);
    check(offset + 24, blocks * 8);  // before sizing anything by `blocks`
    if (blocks > 0 && (block_size == 0 || last_size > block_size))
      throw fail("bad compression header");
    std::string out;
    std::size_t at = offset + 24 + blocks * 8;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t packed = u64(offset + 24 + 8 * b);
      const std::uint64_t size = (b + 1 == blocks && last_size) ? last_size : block_size;
      const char* src = bytes(at, packed);
      // zlib inflates at most 1032:1: a larger claim is damage, not data.
      if (size / 1032 > packed) throw fail("bad compression header");
      const std::size_t start = out.size();
      out.resize(start + size);
      uLongf len = static_cast<uLongf>(size);
      if (uncompress(reinterpret_cast<Bytef*>(&out[start]), &len,
                     reinterpret_cast<const Bytef*>(src), static_cast<uLong>(packed)) != Z_OK ||
          len != size)
        throw fail(fmt::format("zlib block {} of the array at offset {} is damaged", b, offset));
      at += packed;
    }
    return out;
  }

 private:
  void check(std::size_t at, std::uint64_t n) const {
    const std::size_t avail = s_.size() - base_;
    if (at > avail || n > avail - at) throw fail("truncated appended data");
  }
  const std::string& s_;
  std::size_t base_;
  const std::string& source_;
};

template <class T>
void decode(const std::string& bytes, std::vector<double>& out) {
  out.resize(bytes.size() / sizeof(T));
  for (std::size_t k = 0; k < out.size(); ++k) {
    T x;
    std::memcpy(&x, bytes.data() + sizeof(T) * k, sizeof(T));
    out[k] = static_cast<double>(x);
  }
}

std::size_t type_size(const std::string& type) {
  if (type == "Float64" || type == "Int64") return 8;
  if (type == "Float32" || type == "Int32") return 4;
  if (type == "UInt8") return 1;
  return 0;
}

}  // namespace

std::size_t VtkAppended::add_bytes(const void* data, std::size_t bytes) {
  const std::size_t offset = data_.size();
  const char* p = static_cast<const char*>(data);
  if (compression_ == VtkCompression::None) {
    append_u64(bytes);
    data_.append(p, bytes);
    return offset;
  }
  const std::vector<std::string> blocks = compress_blocks(p, bytes);
  append_u64(blocks.size());
  append_u64(kVtkZlibBlockBytes);
  append_u64(bytes % kVtkZlibBlockBytes);  // 0: the last block is full
  for (const std::string& b : blocks) append_u64(b.size());
  for (const std::string& b : blocks) data_ += b;
  return offset;
}

std::string vtk_array_tag(const char* type, const std::string& name, int components,
                          std::size_t offset) {
  return fmt::format(
      R"(<DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset="{}"/>)",
      type, name, components, offset);
}

std::string vtk_field_tag(const char* type, const std::string& name, std::size_t tuples,
                          std::size_t offset) {
  return fmt::format(
      R"(<DataArray type="{}" Name="{}" NumberOfTuples="{}" format="appended" offset="{}"/>)", type,
      name, tuples, offset);
}

std::string vtk_file(const char* type, const std::string& xml, const VtkAppended& appended) {
  const std::string open = fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"{}\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\"{}>\n",
      type,
      appended.compression() == VtkCompression::Zlib ? " compressor=\"vtkZLibDataCompressor\""
                                                     : "");
  const char head[] = "<AppendedData encoding=\"raw\">\n_";
  const char tail[] = "\n</AppendedData>\n</VTKFile>\n";
  std::string out;
  out.reserve(open.size() + xml.size() + sizeof head + appended.data().size() + sizeof tail);
  out += open;
  out += xml;
  out += head;
  out += appended.data();
  out += tail;
  return out;
}

std::string xml_attribute(const std::string& tag, const std::string& key) {
  const std::size_t k = tag.find(" " + key + "=\"");
  if (k == std::string::npos) return "";
  const std::size_t start = k + key.size() + 3;
  return tag.substr(start, tag.find('"', start) - start);
}

std::map<std::string, VtkArray> read_vtk_arrays(const std::string& s, const std::string& source) {
  const auto fail = [&](const std::string& why) { return IoError(source + ": " + why); };
  const std::size_t file = s.find("<VTKFile");
  const std::size_t app = s.find("<AppendedData encoding=\"raw\">");
  if (file == std::string::npos || app == std::string::npos || app < file)
    throw fail("not a VTK XML file with raw appended data");
  const std::string head = s.substr(file, s.find('>', file) - file);
  if (xml_attribute(head, "header_type") != "UInt64") throw fail("header_type is not UInt64");
  const std::string compressor = xml_attribute(head, "compressor");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
    throw fail("unsupported compressor " + compressor);
  const std::size_t underscore = s.find('_', app);
  if (underscore == std::string::npos) throw fail("no appended data");
  const AppendedReader reader(s, underscore + 1, source);
  const auto number = [&](const std::string& text, const char* what) -> std::size_t {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
      throw fail(std::string("bad ") + what + " \"" + text + "\"");
    return std::stoull(text);
  };

  std::map<std::string, VtkArray> arrays;
  for (std::size_t pos = s.find("<DataArray"); pos < app; pos = s.find("<DataArray", pos + 1)) {
    const std::string tag = s.substr(pos, s.find('>', pos) - pos);
    VtkArray a;
    a.type = xml_attribute(tag, "type");
    const std::size_t size = type_size(a.type);
    if (size == 0) throw fail("unsupported type " + a.type);
    const std::string comps = xml_attribute(tag, "NumberOfComponents");
    a.components = comps.empty() ? 1 : static_cast<int>(number(comps, "NumberOfComponents"));
    const std::size_t offset = number(xml_attribute(tag, "offset"), "offset");
    const std::string bytes = compressor.empty() ? reader.raw(offset) : reader.inflate(offset);
    if (bytes.size() % size) throw fail("array " + xml_attribute(tag, "Name") + ": partial value");
    if (a.type == "Float64") decode<double>(bytes, a.values);
    if (a.type == "Float32") decode<float>(bytes, a.values);
    if (a.type == "Int64") decode<std::int64_t>(bytes, a.values);
    if (a.type == "Int32") decode<std::int32_t>(bytes, a.values);
    if (a.type == "UInt8") decode<std::uint8_t>(bytes, a.values);
    arrays[xml_attribute(tag, "Name")] = std::move(a);
  }
  return arrays;
}

}  // namespace sablier
