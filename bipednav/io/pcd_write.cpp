#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/io/lzf.hpp"
#include "bipednav/io/pcd.hpp"

namespace bipednav::io {

namespace {

struct OutField {
  const char* name;
  char type;
  std::size_t size;
};

std::vector<OutField> out_fields(const PointCloud& c) {
  std::vector<OutField> f = {{"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}};
  if (c.has_intensity()) f.push_back({"intensity", 'F', 4});
  if (c.has_time()) f.push_back({"time", 'F', 4});
  if (c.has_ring()) f.push_back({"ring", 'U', 2});
  return f;
}

// Value i of output field k, as bytes at dst; fields are laid out as out_fields() lists them.
void put_value(std::uint8_t* dst, const PointCloud& c, const OutField& f, std::size_t k, std::size_t i) {
  if (k < 3) {
    std::memcpy(dst, &c.points[i][static_cast<int>(k)], 4);
  } else if (f.name[0] == 'i') {
    std::memcpy(dst, &c.intensities[i], 4);
  } else if (f.name[0] == 't') {
    std::memcpy(dst, &c.time_offsets_s[i], 4);
  } else {
    std::memcpy(dst, &c.rings[i], 2);
  }
}

void append_number(std::string& out, const PointCloud& c, const OutField& f, std::size_t k, std::size_t i) {
  char buf[48];
  std::to_chars_result r{};
  if (f.type == 'U') {
    r = std::to_chars(buf, buf + sizeof(buf), c.rings[i]);
  } else {
    float v = 0.0f;
    put_value(reinterpret_cast<std::uint8_t*>(&v), c, f, k, i);
    r = std::to_chars(buf, buf + sizeof(buf), v);  // shortest form that reads back bit-exactly
  }
  out.append(buf, r.ptr);
}

std::string pcd_header(const PointCloud& c, const std::vector<OutField>& f, PcdEncoding e) {
  std::ostringstream fields, sizes, types, counts;
  for (const auto& x : f) {
    fields << ' ' << x.name;
    sizes << ' ' << x.size;
    types << ' ' << x.type;
    counts << " 1";
  }
  const char* data = e == PcdEncoding::ascii ? "ascii" : e == PcdEncoding::binary ? "binary" : "binary_compressed";
  std::ostringstream h;
  h << "# .PCD v0.7 - Point Cloud Data file format (written by bipednav)\nVERSION 0.7\nFIELDS" << fields.str()
    << "\nSIZE" << sizes.str() << "\nTYPE" << types.str() << "\nCOUNT" << counts.str() << "\nWIDTH " << c.size()
    << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << c.size() << "\nDATA " << data << '\n';
  return h.str();
}

}  // namespace

std::string pcd_bytes(const PointCloud& c, PcdEncoding encoding) {
  if (!c.is_consistent()) throw Error("write_pcd: the cloud's optional fields do not match its point count");
  const auto f = out_fields(c);
  std::string out = pcd_header(c, f, encoding);
  const std::size_t n = c.size();
  if (encoding == PcdEncoding::ascii) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < f.size(); ++k) {
        if (k) out += ' ';
        append_number(out, c, f[k], k, i);
      }
      out += '\n';
    }
    return out;
  }
  std::size_t point_size = 0;
  for (const auto& x : f) point_size += x.size;
  std::vector<std::uint8_t> raw(n * point_size);
  const bool field_major = encoding == PcdEncoding::binary_compressed;
  std::size_t offset = 0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    const std::size_t base = field_major ? n * offset : offset, stride = field_major ? f[k].size : point_size;
    for (std::size_t i = 0; i < n; ++i) put_value(raw.data() + base + i * stride, c, f[k], k, i);
    offset += f[k].size;
  }
  if (!field_major) return out.append(reinterpret_cast<const char*>(raw.data()), raw.size());
  const std::vector<std::uint8_t> packed = lzf_compress(raw.data(), raw.size());
  const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(packed.size()), static_cast<std::uint32_t>(raw.size())};
  out.append(reinterpret_cast<const char*>(sizes), 8);
  return out.append(reinterpret_cast<const char*>(packed.data()), packed.size());
}

void write_pcd(const std::filesystem::path& file, const PointCloud& cloud, PcdEncoding encoding) {
  const std::string bytes = pcd_bytes(cloud, encoding);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw FileError(file.string(), "", "cannot open the file for writing");
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw FileError(file.string(), "", "write failed (disk full?)");
}

PcdEncoding pcd_encoding_from_string(const std::string& s) {
  if (s == "ascii") return PcdEncoding::ascii;
  if (s == "binary") return PcdEncoding::binary;
  if (s == "binary_compressed") return PcdEncoding::binary_compressed;
  throw Error("unknown PCD encoding '" + s + "' (expected ascii, binary or binary_compressed)");
}

}  // namespace bipednav::io
