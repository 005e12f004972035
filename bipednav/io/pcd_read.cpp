#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/io/lzf.hpp"
#include "bipednav/io/pcd.hpp"

namespace bipednav::io {
namespace detail {

bool valid_scalar(char kind, std::size_t size) {
  if (kind == 'F') return size == 4 || size == 8;
  if (kind == 'U' || kind == 'I') return size == 1 || size == 2 || size == 4 || size == 8;
  return false;
}

template <typename T>
double load_as(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

double load_scalar(const std::uint8_t* p, char kind, std::size_t size) {
  if (kind == 'F') return size == 4 ? load_as<float>(p) : load_as<double>(p);
  const bool u = kind == 'U';
  switch (size) {
    case 1:
      return u ? load_as<std::uint8_t>(p) : load_as<std::int8_t>(p);
    case 2:
      return u ? load_as<std::uint16_t>(p) : load_as<std::int16_t>(p);
    case 4:
      return u ? load_as<std::uint32_t>(p) : load_as<std::int32_t>(p);
    default:
      return u ? load_as<std::uint64_t>(p) : load_as<std::int64_t>(p);
  }
}

std::string read_file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw FileError(file.string(), "", "cannot open the file for reading (does it exist?)");
  std::ostringstream ss;
  ss << in.rdbuf();
  return std::move(ss).str();
}

}  // namespace detail

namespace {

struct PcdField {
  std::string name;
  std::size_t size = 4;
  char type = 'F';
  std::size_t count = 1;
  std::size_t offset = 0;  // byte offset inside one point record
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t width = 0, height = 1, points = 0, point_size = 0;
  std::string data;
  std::size_t data_offset = 0;  // first byte after the DATA line
  std::size_t data_line = 0;    // 1-based line number of the DATA line
};

std::vector<std::string> split_words(std::string_view line) {
  std::vector<std::string> w;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t s = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > s) w.emplace_back(line.substr(s, i - s));
  }
  return w;
}

class HeaderParser {
 public:
  HeaderParser(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  PcdHeader parse() {
    std::size_t pos = 0, line_no = 0;
    while (pos < bytes_.size()) {
      const std::size_t eol = bytes_.find('\n', pos);
      const std::size_t end = eol == std::string_view::npos ? bytes_.size() : eol;
      ++line_no;
      line_ = "line " + std::to_string(line_no);
      const auto words = split_words(bytes_.substr(pos, end - pos));
      pos = eol == std::string_view::npos ? bytes_.size() : eol + 1;
      if (words.empty() || words[0][0] == '#') continue;
      if (words[0] == "DATA") {
        keyword(words);
        h_.data_offset = pos;
        h_.data_line = line_no;
        return finish();
      }
      keyword(words);
    }
    throw FileError(name_, "header", "no DATA line (expected 'DATA ascii|binary|binary_compressed')");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw FileError(name_, line_, what); }

  std::size_t to_size(const std::string& w, const std::string& key) const {
    std::size_t v = 0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size())
      fail(key + ": expected a non-negative integer, found '" + w + "'");
    return v;
  }

  // a * b, failing instead of wrapping around (found by fuzz/fuzz_pcd).
  std::size_t product(std::size_t a, std::size_t b, const std::string& what) const {
    if (b != 0 && a > std::numeric_limits<std::size_t>::max() / b) fail(what + " overflows");
    return a * b;
  }

  void per_field(const std::vector<std::string>& w, std::size_t expected) const {
    if (h_.fields.empty()) fail(w[0] + " before FIELDS: expected FIELDS first");
    if (w.size() - 1 != expected)
      fail(w[0] + " has " + std::to_string(w.size() - 1) + " entries, expected " + std::to_string(expected) +
           " (one per FIELDS entry)");
  }

  void keyword(const std::vector<std::string>& w) {
    const std::string& k = w[0];
    seen_.push_back(k);
    const std::size_t nf = h_.fields.size();
    if (k == "VERSION") return;
    if (k == "FIELDS" || k == "COLUMNS") {
      if (w.size() < 2) fail("FIELDS: expected at least one field name");
      for (std::size_t i = 1; i < w.size(); ++i) h_.fields.push_back({w[i]});
    } else if (k == "SIZE") {
      per_field(w, nf);
      for (std::size_t i = 0; i < nf; ++i) h_.fields[i].size = to_size(w[i + 1], "SIZE");
    } else if (k == "TYPE") {
      per_field(w, nf);
      for (std::size_t i = 0; i < nf; ++i) {
        if (w[i + 1].size() != 1) fail("TYPE: expected F, U or I, found '" + w[i + 1] + "'");
        h_.fields[i].type = w[i + 1][0];
      }
    } else if (k == "COUNT") {
      per_field(w, nf);
      for (std::size_t i = 0; i < nf; ++i) h_.fields[i].count = to_size(w[i + 1], "COUNT");
    } else if (k == "WIDTH") {
      h_.width = one_size(w);
    } else if (k == "HEIGHT") {
      h_.height = one_size(w);
    } else if (k == "POINTS") {
      h_.points = one_size(w);
    } else if (k == "VIEWPOINT") {
      if (w.size() != 8) fail("VIEWPOINT: expected 7 numbers (tx ty tz qw qx qy qz)");
    } else if (k == "DATA") {
      if (w.size() != 2 || (w[1] != "ascii" && w[1] != "binary" && w[1] != "binary_compressed"))
        fail("DATA: expected ascii, binary or binary_compressed");
      h_.data = w[1];
    } else {
      fail("unknown header keyword '" + k +
           "' (expected VERSION, FIELDS, SIZE, TYPE, COUNT, WIDTH, HEIGHT, "
           "VIEWPOINT, POINTS or DATA)");
    }
  }

  std::size_t one_size(const std::vector<std::string>& w) const {
    if (w.size() != 2) fail(w[0] + ": expected exactly one integer");
    return to_size(w[1], w[0]);
  }

  bool has(const std::string& k) const { return std::find(seen_.begin(), seen_.end(), k) != seen_.end(); }

  PcdHeader finish() {
    for (const char* k : {"FIELDS", "SIZE", "TYPE", "WIDTH"})
      if (!has(k) && !(std::string(k) == "FIELDS" && has("COLUMNS")))
        fail(std::string("header has no ") + k + " line (expected before DATA)");
    const std::size_t wh = product(h_.width, h_.height, "WIDTH x HEIGHT");
    if (!has("POINTS")) h_.points = wh;
    if (h_.points != wh)
      fail("POINTS " + std::to_string(h_.points) + " does not match WIDTH x HEIGHT = " + std::to_string(wh));
    for (auto& f : h_.fields) {
      if (!detail::valid_scalar(f.type, f.size))
        throw FileError(name_, "field '" + f.name + "'",
                        "unsupported TYPE " + std::string(1, f.type) + " with SIZE " + std::to_string(f.size) +
                            " (expected F 4/8, U or I 1/2/4/8)");
      if (f.count == 0) throw FileError(name_, "field '" + f.name + "'", "COUNT 0 (expected >= 1)");
      f.offset = h_.point_size;
      h_.point_size += product(f.size, f.count, "field '" + f.name + "' SIZE x COUNT");
      if (h_.point_size < f.offset) fail("the point size overflows");
    }
    product(h_.points, h_.point_size, "POINTS x point size");
    return h_;
  }

  std::string_view bytes_;
  const std::string& name_;
  std::string line_;
  std::vector<std::string> seen_;
  PcdHeader h_;
};

enum class Target { x, y, z, intensity, time, ring };

struct Mapped {
  Target target;
  const PcdField* field;
  std::size_t column;  // index of the field's first value in an ASCII line
};

std::vector<Mapped> map_fields(const PcdHeader& h, const std::string& name) {
  std::vector<Mapped> m;
  std::size_t column = 0;
  bool xyz[3] = {false, false, false};
  for (const auto& f : h.fields) {
    std::optional<Target> t;
    if (f.name == "x" || f.name == "y" || f.name == "z") {
      if (f.count != 1) throw FileError(name, "field '" + f.name + "'", "COUNT must be 1 for a coordinate");
      t = static_cast<Target>(f.name[0] - 'x');
      xyz[f.name[0] - 'x'] = true;
    } else if (f.count == 1 && f.name == "intensity") {
      t = Target::intensity;
    } else if (f.count == 1 && (f.name == "time" || f.name == "t")) {
      t = Target::time;
    } else if (f.count == 1 && f.name == "ring") {
      if (f.type == 'F') throw FileError(name, "field 'ring'", "expected an integer TYPE (U or I), found F");
      t = Target::ring;
    }
    if (t) m.push_back({*t, &f, column});
    column += f.count;
  }
  for (int a = 0; a < 3; ++a)
    if (!xyz[a])
      throw FileError(name, "FIELDS", std::string("no field '") + char('x' + a) + "' (x, y, z are required)");
  return m;
}

void prepare(PointCloud& c, const std::vector<Mapped>& m, std::size_t n) {
  c.points.resize(n);
  for (const auto& f : m) {
    if (f.target == Target::intensity) c.intensities.resize(n);
    if (f.target == Target::time) c.time_offsets_s.resize(n);
    if (f.target == Target::ring) c.rings.resize(n);
  }
}

void store(PointCloud& c, const Mapped& f, std::size_t i, double v, const std::string& name) {
  switch (f.target) {
    case Target::x:
    case Target::y:
    case Target::z:
      c.points[i][static_cast<int>(f.target)] = static_cast<float>(v);
      break;
    case Target::intensity:
      c.intensities[i] = static_cast<float>(v);
      break;
    case Target::time:
      c.time_offsets_s[i] = static_cast<float>(f.field->type == 'F' ? v : v * 1e-9);
      break;
    case Target::ring:
      if (!(v >= 0.0 && v <= 65535.0))
        throw FileError(name, "field 'ring', point " + std::to_string(i), "expected a value in [0, 65535]");
      c.rings[i] = static_cast<std::uint16_t>(v);
      break;
  }
}

// Binary layouts: value i of a field sits at base + i * stride.
void read_binary(PointCloud& c, const std::vector<Mapped>& m, const PcdHeader& h, const std::uint8_t* data,
                 bool field_major, const std::string& name) {
  const std::size_t n = h.points;
  for (const auto& f : m) {
    const std::size_t base = field_major ? n * f.field->offset : f.field->offset;
    const std::size_t stride = field_major ? f.field->size * f.field->count : h.point_size;
    const std::uint8_t* p = data + base;
    if (f.target <= Target::z && f.field->type == 'F' && f.field->size == 4) {
      const int axis = static_cast<int>(f.target);
      for (std::size_t i = 0; i < n; ++i, p += stride) std::memcpy(&c.points[i][axis], p, 4);
      continue;
    }
    for (std::size_t i = 0; i < n; ++i, p += stride)
      store(c, f, i, detail::load_scalar(p, f.field->type, f.field->size), name);
  }
}

void read_ascii(PointCloud& c, const std::vector<Mapped>& m, const PcdHeader& h, std::string_view bytes,
                const std::string& name) {
  std::size_t columns = 0;
  for (const auto& f : h.fields) columns += f.count;
  std::size_t pos = h.data_offset, line_no = h.data_line, i = 0;
  while (pos < bytes.size() && i < h.points) {
    const std::size_t eol = std::min(bytes.find('\n', pos), bytes.size());
    const auto words = split_words(bytes.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_no;
    if (words.empty()) continue;
    const std::string where = "line " + std::to_string(line_no);
    if (words.size() != columns)
      throw FileError(name, where,
                      "expected " + std::to_string(columns) + " values, found " + std::to_string(words.size()));
    for (const auto& f : m) {
      const std::string& w = words[f.column];
      double v = 0.0;
      const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
      if (r.ec != std::errc() || r.ptr != w.data() + w.size())
        throw FileError(name, where + ", field '" + f.field->name + "'", "expected a number, found '" + w + "'");
      store(c, f, i, v, name);
    }
    ++i;
  }
  if (i != h.points)
    throw FileError(name, "DATA",
                    "truncated: expected " + std::to_string(h.points) + " points, found " + std::to_string(i));
}

std::uint32_t load_u32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

void read_compressed(PointCloud& c, const std::vector<Mapped>& m, const PcdHeader& h, std::string_view bytes,
                     const std::string& name) {
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data()) + h.data_offset;
  const std::size_t avail = bytes.size() - h.data_offset;
  if (avail < 8) throw FileError(name, "DATA", "truncated: expected 8 bytes of compressed/raw sizes");
  const std::size_t csize = load_u32(data), rsize = load_u32(data + 4);
  const std::size_t expected = h.points * h.point_size;
  if (rsize != expected)
    throw FileError(name, "DATA",
                    "uncompressed size " + std::to_string(rsize) + " does not match POINTS x " +
                        "point size = " + std::to_string(expected));
  if (avail - 8 < csize)
    throw FileError(
        name, "DATA",
        "truncated: expected " + std::to_string(csize) + " bytes of LZF data, found " + std::to_string(avail - 8));
  // One 3-byte LZF back reference yields at most 264 bytes; more claimed output is corrupt and must
  // not size an allocation (found by fuzz/fuzz_pcd).
  if (rsize > 88 * csize)
    throw FileError(name, "DATA",
                    "corrupt LZF data: " + std::to_string(csize) + " compressed bytes cannot hold " +
                        std::to_string(rsize) + " bytes");
  if (expected == 0) return;
  const auto raw = lzf_decompress(data + 8, csize, rsize);
  if (!raw)
    throw FileError(name, "DATA",
                    "corrupt LZF data (expected a valid LZF stream of " + std::to_string(rsize) + " bytes)");
  prepare(c, m, h.points);
  read_binary(c, m, h, raw->data(), true, name);
}

}  // namespace

PointCloud parse_pcd(std::string_view bytes, const std::string& name) {
  const PcdHeader h = HeaderParser(bytes, name).parse();
  const std::vector<Mapped> m = map_fields(h, name);
  PointCloud c;
  // The cloud is sized only once the data is known to hold POINTS (found by fuzz/fuzz_pcd).
  if (h.data == "ascii") {
    if (h.points > bytes.size() - h.data_offset)
      throw FileError(name, "DATA",
                      "truncated: expected " + std::to_string(h.points) + " points, found only " +
                          std::to_string(bytes.size() - h.data_offset) + " bytes of data");
    prepare(c, m, h.points);
    read_ascii(c, m, h, bytes, name);
  } else if (h.data == "binary") {
    const std::size_t need = h.points * h.point_size, avail = bytes.size() - h.data_offset;
    if (avail < need)
      throw FileError(name, "DATA",
                      "truncated: expected " + std::to_string(need) + " bytes of binary data (" +
                          std::to_string(h.points) + " points), found " + std::to_string(avail));
    prepare(c, m, h.points);
    read_binary(c, m, h, reinterpret_cast<const std::uint8_t*>(bytes.data()) + h.data_offset, false, name);
  } else {
    read_compressed(c, m, h, bytes, name);
  }
  return c;
}

PointCloud read_pcd(const std::filesystem::path& file) {
  const std::string bytes = detail::read_file_bytes(file);
  return parse_pcd(bytes, file.string());
}

}  // namespace bipednav::io
