#include "bipednav/io/map_server.hpp"

#include <cairo.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <system_error>

#include "bipednav/common/error.hpp"

namespace bipednav::io {

namespace {

// Next whitespace-separated PGM header token, skipping '#' comments.
std::string pgm_token(std::istream& in) {
  std::string tok;
  char c;
  while (in.get(c)) {
    if (c == '#') {
      std::string rest;
      std::getline(in, rest);
      if (!tok.empty()) break;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!tok.empty()) break;
      continue;
    }
    tok += c;
  }
  return tok;
}

int pgm_int(std::istream& in, const std::string& file, const std::string& field) {
  const std::string t = pgm_token(in);
  try {
    std::size_t used = 0;
    const int v = std::stoi(t, &used);
    if (used == t.size() && v >= 0) return v;
  } catch (const std::exception&) {
  }
  throw FileError(file, field, "expected a non-negative integer, got '" + t + "'");
}

}  // namespace

GrayImage read_pgm(const std::filesystem::path& path) {
  const std::string f = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(f, "", "cannot open the file for reading (does it exist?)");
  const std::string magic = pgm_token(in);
  if (magic != "P5" && magic != "P2")
    throw FileError(f, "magic", "expected P5 or P2 (a PGM image), got '" + magic + "'");
  GrayImage img;
  img.width = pgm_int(in, f, "width");
  img.height = pgm_int(in, f, "height");
  const int maxval = pgm_int(in, f, "maxval");
  if (img.width <= 0 || img.height <= 0 || std::size_t(img.width) * img.height > 400'000'000u)
    throw FileError(f, "width/height", "expected a size between 1 and 4e8 pixels");
  if (maxval < 1 || maxval > 65535) throw FileError(f, "maxval", "expected 1..65535");
  const std::size_t n = std::size_t(img.width) * img.height;
  // The header alone must not size the buffers (a 30-byte file asked for 800 MB; found by
  // fuzz/fuzz_map_server): P5 needs 1 or 2 bytes a pixel, P2 at least 2 characters.
  const std::streamoff start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff left = in.tellg() - start;
  in.seekg(start);
  const std::size_t least = n * (magic == "P2" || maxval > 255 ? 2 : 1);
  if (start >= 0 && left >= 0 && static_cast<std::size_t>(left) + (magic == "P2" ? 1 : 0) < least)
    throw FileError(f, "pixels",
                    "expected " + std::to_string(least) + " bytes of pixel data, got " + std::to_string(left) +
                        " (truncated file?)");
  img.pixels.resize(n);
  const auto to8 = [&](unsigned v) {
    return static_cast<std::uint8_t>(std::lround(255.0 * std::min<unsigned>(v, maxval) / maxval));
  };
  if (magic == "P2") {
    for (std::size_t i = 0; i < n; ++i)
      img.pixels[i] = to8(static_cast<unsigned>(pgm_int(in, f, "pixel " + std::to_string(i))));
    return img;
  }
  const std::size_t bytes = maxval > 255 ? 2 : 1;
  std::vector<unsigned char> raw(n * bytes);
  in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size()));
  if (static_cast<std::size_t>(in.gcount()) != raw.size())
    throw FileError(f, "pixels",
                    "expected " + std::to_string(raw.size()) + " bytes of pixel data, got " +
                        std::to_string(in.gcount()) + " (truncated file?)");
  for (std::size_t i = 0; i < n; ++i)
    img.pixels[i] = to8(bytes == 2 ? (unsigned(raw[2 * i]) << 8) | raw[2 * i + 1] : raw[i]);
  return img;
}

GrayImage read_png_gray(const std::filesystem::path& path) {
  const std::string f = path.string();
  if (std::error_code ec; !std::filesystem::exists(path, ec))
    throw FileError(f, "", "cannot open the file for reading (does it exist?)");
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> s(cairo_image_surface_create_from_png(f.c_str()),
                                                                       cairo_surface_destroy);
  if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS)
    throw FileError(
        f, "", std::string("not a readable PNG image (") + cairo_status_to_string(cairo_surface_status(s.get())) + ")");
  cairo_surface_flush(s.get());
  GrayImage img;
  img.width = cairo_image_surface_get_width(s.get());
  img.height = cairo_image_surface_get_height(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  const cairo_format_t fmt = cairo_image_surface_get_format(s.get());
  const unsigned char* data = cairo_image_surface_get_data(s.get());
  if (!data || (fmt != CAIRO_FORMAT_ARGB32 && fmt != CAIRO_FORMAT_RGB24 && fmt != CAIRO_FORMAT_A8))
    throw FileError(f, "", "unsupported PNG pixel format");
  const std::size_t n = std::size_t(img.width) * img.height;
  img.pixels.resize(n);
  if (fmt == CAIRO_FORMAT_ARGB32) img.alpha.resize(n);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = std::size_t(y) * img.width + x;
      if (fmt == CAIRO_FORMAT_A8) {
        img.pixels[i] = data[std::size_t(y) * stride + x];
        continue;
      }
      std::uint32_t px;
      std::memcpy(&px, data + std::size_t(y) * stride + 4 * x, 4);
      const unsigned a = fmt == CAIRO_FORMAT_ARGB32 ? px >> 24 : 255;
      unsigned r = (px >> 16) & 0xff, g = (px >> 8) & 0xff, b = px & 0xff;
      if (a > 0 && a < 255) {  // cairo premultiplies alpha
        r = r * 255 / a;
        g = g * 255 / a;
        b = b * 255 / a;
      }
      img.pixels[i] = static_cast<std::uint8_t>((r + g + b) / 3);
      if (!img.alpha.empty()) img.alpha[i] = static_cast<std::uint8_t>(a);
    }
  }
  return img;
}

namespace {

double yaml_number(const YAML::Node& root, const std::string& key, const std::string& file, bool required,
                   double fallback) {
  const YAML::Node n = root[key];
  if (!n) {
    if (required) throw FileError(file, key, "required key is missing");
    return fallback;
  }
  try {
    const double v = n.as<double>();
    if (std::isfinite(v)) return v;
  } catch (const YAML::Exception&) {
  }
  throw FileError(file, key, "expected a finite number");
}

// An image given where its YAML is expected (`costmap info maze.png`): named as such rather than
// reported as a YAML syntax error.
void reject_image_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  in.read(magic, sizeof magic);
  const std::string head(magic, static_cast<std::size_t>(in.gcount()));
  const bool png = head.rfind("\x89PNG", 0) == 0;
  const bool pgm = head.size() >= 2 && head[0] == 'P' && (head[1] == '2' || head[1] == '5');
  if (png || pgm)
    throw FileError(file.string(), "",
                    std::string("a ") + (png ? "PNG" : "PGM") +
                        " image, not a map_server YAML: give the YAML file that names the image (image:, "
                        "resolution:, origin:)");
}

MapServerMetadata parse_metadata(const std::filesystem::path& yaml_path) {
  const std::string f = yaml_path.string();
  if (std::error_code ec; !std::filesystem::exists(yaml_path, ec))
    throw FileError(f, "", "cannot open the file for reading (does it exist?)");
  reject_image_file(yaml_path);
  YAML::Node root;
  try {
    root = YAML::LoadFile(f);
  } catch (const YAML::Exception& e) {
    throw FileError(f, "line " + std::to_string(e.mark.line + 1), "invalid YAML: " + e.msg);
  }
  if (!root.IsMap()) throw FileError(f, "", "expected a YAML mapping with image, resolution, origin");
  MapServerMetadata m;
  try {
    if (!root["image"]) throw FileError(f, "image", "required key is missing");
    m.image = root["image"].as<std::string>();
    if (root["mode"]) m.mode = root["mode"].as<std::string>();
  } catch (const YAML::Exception&) {
    throw FileError(f, "image/mode", "expected a string");
  }
  if (m.mode != "trinary" && m.mode != "scale")
    throw FileError(f, "mode", "expected trinary or scale, got '" + m.mode + "'");
  m.resolution_m = yaml_number(root, "resolution", f, true, 0.0);
  if (m.resolution_m <= 0.0) throw FileError(f, "resolution", "expected > 0 m per pixel");
  const YAML::Node o = root["origin"];
  if (!o) throw FileError(f, "origin", "required key is missing");
  if (!o.IsSequence() || o.size() != 3) throw FileError(f, "origin", "expected [x, y, yaw]");
  double xyz[3];
  for (std::size_t i = 0; i < 3; ++i) {
    try {
      xyz[i] = o[i].as<double>();
    } catch (const YAML::Exception&) {
      throw FileError(f, "origin[" + std::to_string(i) + "]", "expected a number");
    }
    if (!std::isfinite(xyz[i])) throw FileError(f, "origin[" + std::to_string(i) + "]", "expected a finite number");
  }
  m.origin_x_m = xyz[0];
  m.origin_y_m = xyz[1];
  m.origin_yaw_rad = xyz[2];
  if (std::abs(m.origin_yaw_rad) > 1e-9)
    throw FileError(f, "origin[2]", "expected yaw 0 (rotated maps are not supported)");
  if (const YAML::Node n = root["negate"]) {
    const std::string s = n.Scalar();
    if (s == "0" || s == "false" || s == "False")
      m.negate = false;
    else if (s == "1" || s == "true" || s == "True")
      m.negate = true;
    else
      throw FileError(f, "negate", "expected 0 or 1, got '" + s + "'");
  }
  m.occupied_thresh = yaml_number(root, "occupied_thresh", f, false, m.occupied_thresh);
  m.free_thresh = yaml_number(root, "free_thresh", f, false, m.free_thresh);
  if (m.occupied_thresh < 0.0 || m.occupied_thresh > 1.0) throw FileError(f, "occupied_thresh", "expected in [0, 1]");
  if (m.free_thresh < 0.0 || m.free_thresh > m.occupied_thresh)
    throw FileError(f, "free_thresh", "expected in [0, occupied_thresh]");
  return m;
}

}  // namespace

MapServerFile read_map_server_file(const std::filesystem::path& yaml_path) {
  MapServerFile file{parse_metadata(yaml_path), {}};
  const MapServerMetadata& m = file.metadata;
  std::filesystem::path image = m.image;
  if (image.is_relative()) image = yaml_path.parent_path() / image;
  if (std::error_code ec; !std::filesystem::is_regular_file(image, ec))
    throw FileError(yaml_path.string(), "image", "the image '" + image.string() + "' does not exist");
  std::string ext = image.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".pgm")
    file.image = read_pgm(image);
  else if (ext == ".png")
    file.image = read_png_gray(image);
  else
    throw FileError(yaml_path.string(), "image", "expected a .pgm or .png file, got '" + m.image + "'");
  return file;
}

void write_map_server_file(const std::filesystem::path& yaml_path, const GrayImage& image, double resolution_m,
                           double origin_x_m, double origin_y_m) {
  if (image.width < 0 || image.height < 0 || image.pixels.size() != std::size_t(image.width) * image.height)
    throw Error("write_map_server_file: the image needs width * height pixels");
  std::filesystem::path pgm = yaml_path;
  pgm.replace_extension(".pgm");
  {
    std::ofstream out(pgm, std::ios::binary);
    if (!out) throw FileError(pgm.string(), "", "cannot open the file for writing");
    out << "P5\n# bipednav costmap\n" << image.width << " " << image.height << "\n255\n";
    out.write(reinterpret_cast<const char*>(image.pixels.data()), static_cast<std::streamsize>(image.pixels.size()));
    if (!out) throw FileError(pgm.string(), "", "write failed");
  }
  std::ofstream y(yaml_path);
  if (!y) throw FileError(yaml_path.string(), "", "cannot open the file for writing");
  y.precision(17);
  y << "image: " << pgm.filename().string() << "\nresolution: " << resolution_m << "\norigin: [" << origin_x_m << ", "
    << origin_y_m << ", 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n";
  if (!y) throw FileError(yaml_path.string(), "", "write failed");
}

}  // namespace bipednav::io
