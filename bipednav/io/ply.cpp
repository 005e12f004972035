#include "bipednav/io/ply.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"

namespace bipednav::io {
namespace {

struct Scalar {
  char kind = 'F';
  std::size_t size = 4;
};

struct PlyProperty {
  std::string name;
  Scalar type;
  bool is_list = false;
  Scalar count_type;  // for lists
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> props;
};

struct PlyHeader {
  bool ascii = true;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;
  std::size_t data_line = 0;
};

std::optional<Scalar> scalar_type(const std::string& t) {
  if (t == "char" || t == "int8") return Scalar{'I', 1};
  if (t == "uchar" || t == "uint8") return Scalar{'U', 1};
  if (t == "short" || t == "int16") return Scalar{'I', 2};
  if (t == "ushort" || t == "uint16") return Scalar{'U', 2};
  if (t == "int" || t == "int32") return Scalar{'I', 4};
  if (t == "uint" || t == "uint32") return Scalar{'U', 4};
  if (t == "float" || t == "float32") return Scalar{'F', 4};
  if (t == "double" || t == "float64") return Scalar{'F', 8};
  return std::nullopt;
}

std::vector<std::string> words_of(std::string_view line) {
  std::vector<std::string> w;
  std::istringstream ss{std::string(line)};
  for (std::string s; ss >> s;) w.push_back(s);
  return w;
}

class PlyHeaderParser {
 public:
  PlyHeaderParser(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  PlyHeader parse() {
    std::size_t pos = 0, line_no = 0;
    while (pos < bytes_.size()) {
      const std::size_t eol = std::min(bytes_.find('\n', pos), bytes_.size());
      const auto w = words_of(bytes_.substr(pos, eol - pos));
      pos = eol + 1;
      where_ = "line " + std::to_string(++line_no);
      if (line_no == 1) {
        if (w.size() != 1 || w[0] != "ply") fail("expected the magic word 'ply'");
        continue;
      }
      if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
      if (w[0] == "end_header") {
        if (!format_seen_) fail("end_header before a format line");
        h_.data_offset = std::min(pos, bytes_.size());
        h_.data_line = line_no;
        return h_;
      }
      keyword(w);
    }
    throw FileError(name_, "header", "no end_header line (expected a PLY header)");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw FileError(name_, where_, what); }

  Scalar type_of(const std::string& t) const {
    const auto s = scalar_type(t);
    if (!s) fail("unknown property type '" + t + "' (expected char/uchar/short/ushort/int/uint/float/double)");
    return *s;
  }

  void keyword(const std::vector<std::string>& w) {
    if (w[0] == "format") {
      if (w.size() != 3) fail("format: expected 'format ascii|binary_little_endian 1.0'");
      if (w[1] == "binary_big_endian")
        fail(
            "format binary_big_endian is not supported (expected ascii or "
            "binary_little_endian)");
      if (w[1] != "ascii" && w[1] != "binary_little_endian")
        fail("format: expected ascii or binary_little_endian, found '" + w[1] + "'");
      h_.ascii = w[1] == "ascii";
      format_seen_ = true;
    } else if (w[0] == "element") {
      std::size_t n = 0;
      if (w.size() != 3 || std::from_chars(w[2].data(), w[2].data() + w[2].size(), n).ec != std::errc())
        fail("element: expected 'element NAME COUNT'");
      h_.elements.push_back({w[1], n, {}});
    } else if (w[0] == "property") {
      if (h_.elements.empty()) fail("property before any element");
      if (w.size() == 5 && w[1] == "list") {
        h_.elements.back().props.push_back({w[4], type_of(w[3]), true, type_of(w[2])});
      } else if (w.size() == 3) {
        h_.elements.back().props.push_back({w[2], type_of(w[1]), false, Scalar{}});
      } else {
        fail("property: expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
    } else {
      fail("unknown header keyword '" + w[0] + "' (expected format, comment, element, property or end_header)");
    }
  }

  std::string_view bytes_;
  const std::string& name_;
  std::string where_;
  bool format_seen_ = false;
  PlyHeader h_;
};

// Column (ascii) of x, y, z, intensity within a vertex; -1 when absent.
struct VertexMap {
  int col[4] = {-1, -1, -1, -1};
};

VertexMap map_vertex(const PlyElement& v, const std::string& name) {
  VertexMap m;
  const char* names[4] = {"x", "y", "z", "intensity"};
  for (std::size_t i = 0; i < v.props.size(); ++i)
    for (int k = 0; k < 4; ++k)
      if (v.props[i].name == names[k]) {
        if (v.props[i].is_list)
          throw FileError(name, "property '" + v.props[i].name + "'", "expected a scalar, found a list");
        m.col[k] = static_cast<int>(i);
      }
  for (int k = 0; k < 3; ++k)
    if (m.col[k] < 0)
      throw FileError(name, "element vertex", std::string("no property '") + names[k] + "' (x, y, z are required)");
  return m;
}

void store_vertex(PointCloud& c, const VertexMap& m, const double* vals) {
  c.points.emplace_back(static_cast<float>(vals[m.col[0]]), static_cast<float>(vals[m.col[1]]),
                        static_cast<float>(vals[m.col[2]]));
  if (m.col[3] >= 0) c.intensities.push_back(static_cast<float>(vals[m.col[3]]));
}

class BinaryCursor {
 public:
  BinaryCursor(std::string_view b, std::size_t pos, const std::string& name) : b_(b), pos_(pos), name_(name) {}
  double next(Scalar s, const std::string& what) {
    if (pos_ + s.size > b_.size())
      throw FileError(name_, what, "truncated: expected " + std::to_string(s.size) + " more bytes");
    const double v = detail::load_scalar(reinterpret_cast<const std::uint8_t*>(b_.data()) + pos_, s.kind, s.size);
    pos_ += s.size;
    return v;
  }
  // Reads one item of an element; scalar values go to vals (lists are skipped).
  void item(const PlyElement& e, std::size_t index, std::vector<double>& vals) {
    for (std::size_t p = 0; p < e.props.size(); ++p) {
      const auto& pr = e.props[p];
      const std::string what = "element " + e.name + " " + std::to_string(index) + ", property '" + pr.name + "'";
      if (!pr.is_list) {
        vals[p] = next(pr.type, what);
        continue;
      }
      const double n = next(pr.count_type, what);
      // Checked before the cast: a float length of 1e30 or inf was undefined (found by fuzz/fuzz_ply).
      if (!(n >= 0.0) || n != std::floor(n) || n * static_cast<double>(pr.type.size) > static_cast<double>(left()))
        throw FileError(name_, what, "expected a non-negative whole list length that fits in the file");
      for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) next(pr.type, what);
    }
  }

 private:
  std::size_t left() const { return b_.size() - pos_; }

  std::string_view b_;
  std::size_t pos_;
  const std::string& name_;
};

PointCloud read_binary(const PlyHeader& h, std::string_view bytes, const std::string& name) {
  PointCloud c;
  BinaryCursor cur(bytes, h.data_offset, name);
  for (const auto& e : h.elements) {
    std::vector<double> vals(e.props.size());
    const bool is_vertex = e.name == "vertex";
    const VertexMap m = is_vertex ? map_vertex(e, name) : VertexMap{};
    if (e.props.empty()) continue;  // no bytes per item: a huge count would spin (fuzz/fuzz_ply)
    for (std::size_t i = 0; i < e.count; ++i) {
      cur.item(e, i, vals);
      if (is_vertex) store_vertex(c, m, vals.data());
    }
    if (is_vertex) return c;
  }
  throw FileError(name, "header", "no 'vertex' element");
}

PointCloud read_ascii(const PlyHeader& h, std::string_view bytes, const std::string& name) {
  PointCloud c;
  std::size_t pos = h.data_offset, line_no = h.data_line;
  for (const auto& e : h.elements) {
    const bool is_vertex = e.name == "vertex";
    const VertexMap m = is_vertex ? map_vertex(e, name) : VertexMap{};
    std::vector<double> vals(e.props.size());
    for (std::size_t i = 0; i < e.count;) {
      if (pos >= bytes.size())
        throw FileError(name, "element " + e.name,
                        "truncated: expected " + std::to_string(e.count) + " items, found " + std::to_string(i));
      const std::size_t eol = std::min(bytes.find('\n', pos), bytes.size());
      const auto w = words_of(bytes.substr(pos, eol - pos));
      pos = eol + 1;
      ++line_no;
      if (w.empty()) continue;
      ++i;
      if (!is_vertex) continue;
      const std::string where = "line " + std::to_string(line_no);
      if (w.size() < e.props.size())
        throw FileError(
            name, where,
            "expected " + std::to_string(e.props.size()) + " vertex values, found " + std::to_string(w.size()));
      for (int k = 0; k < 4; ++k) {
        if (m.col[k] < 0) continue;
        const std::string& s = w[static_cast<std::size_t>(m.col[k])];
        const auto r = std::from_chars(s.data(), s.data() + s.size(), vals[static_cast<std::size_t>(m.col[k])]);
        if (r.ec != std::errc() || r.ptr != s.data() + s.size())
          throw FileError(name, where + ", property '" + e.props[static_cast<std::size_t>(m.col[k])].name + "'",
                          "expected a number, found '" + s + "'");
      }
      store_vertex(c, m, vals.data());
    }
    if (is_vertex) return c;
  }
  throw FileError(name, "header", "no 'vertex' element");
}

}  // namespace

PointCloud parse_ply(std::string_view bytes, const std::string& name) {
  const PlyHeader h = PlyHeaderParser(bytes, name).parse();
  return h.ascii ? read_ascii(h, bytes, name) : read_binary(h, bytes, name);
}

PointCloud read_ply(const std::filesystem::path& file) {
  const std::string bytes = detail::read_file_bytes(file);
  return parse_ply(bytes, file.string());
}

}  // namespace bipednav::io
