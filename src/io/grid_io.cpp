// Grids (images and volumes): .pgm/.pbm, .png, .npy and raw.
#include <png.h>

#include <csetjmp>
#include <cstring>

#include "gpugeom/grid_view.hpp"
#include "gpugeom/io.hpp"
#include "exec/scalar_table.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io {
using namespace detail;

std::int64_t Grid::count() const {
  std::int64_t n = 1;
  for (auto s : shape) n *= s;
  return shape.empty() ? 0 : n;
}
double Grid::value(std::int64_t i) const {
  const unsigned char* p = data.data() + std::size_t(i) * scalar_size(type);
  if (type == ScalarType::Bool) return p[0] ? 1.0 : 0.0;  // (any non-zero byte is true)
  return visit_scalar(type, [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return double(v);
  });
}

namespace {

void check_shape(const std::vector<std::int64_t>& shape, const std::string& name) {
  if (shape.size() < 2 || shape.size() > 8)
    parse_fail(name, 0,
               "a grid must have 2 to 8 dimensions, this one has " + std::to_string(shape.size()));
  for (auto s : shape)
    if (s <= 0) parse_fail(name, 0, "grid dimensions must be positive");
}

// Netpbm header: magic, width, height, (maxval), with '#' comments; returns the body offset.
Grid parse_pnm(const std::string& b, const std::string& name) {
  std::size_t pos = 0;
  auto token = [&]() -> std::string {
    while (pos < b.size()) {
      if (b[pos] == '#') {
        while (pos < b.size() && b[pos] != '\n') ++pos;
      } else if (std::isspace((unsigned char)b[pos])) {
        ++pos;
      } else {
        break;
      }
    }
    std::size_t s = pos;
    while (pos < b.size() && !std::isspace((unsigned char)b[pos]) && b[pos] != '#') ++pos;
    if (s == pos) parse_fail(name, 0, "truncated Netpbm header");
    return b.substr(s, pos - s);
  };
  const std::string magic = token();
  if (magic != "P1" && magic != "P2" && magic != "P4" && magic != "P5")
    parse_fail(
        name, 0,
        "unsupported Netpbm type '" + magic + "': expected P1, P2, P4 or P5 (grey or bitmap)");
  std::int64_t w, h, maxv = 1;
  if (!to_int64(token(), w) || !to_int64(token(), h) || w <= 0 || h <= 0 || w > (1 << 24) ||
      h > (1 << 24))
    parse_fail(name, 0, "bad image width/height");
  const bool bitmap = magic == "P1" || magic == "P4";
  if (!bitmap && (!to_int64(token(), maxv) || maxv <= 0 || maxv > 65535))
    parse_fail(name, 0, "bad maxval (expected 1..65535)");
  Grid g;
  g.shape = {h, w};
  g.type = maxv > 255 ? ScalarType::U16 : ScalarType::U8;
  const std::int64_t n = w * h;
  const bool ascii = magic == "P1" || magic == "P2";
  if (!ascii) ++pos;  // the single whitespace after the header
  if (ascii) {
    if (std::uint64_t(n) > b.size()) parse_fail(name, 0, "image body is truncated");
    g.data.resize(std::size_t(n) * scalar_size(g.type));
    for (std::int64_t i = 0; i < n; ++i) {
      std::int64_t v;
      if (magic == "P1") {  // bits may be written without separators
        while (pos < b.size() && (std::isspace((unsigned char)b[pos]) || b[pos] == '#')) {
          if (b[pos] == '#')
            while (pos < b.size() && b[pos] != '\n') ++pos;
          else
            ++pos;
        }
        if (pos >= b.size() || (b[pos] != '0' && b[pos] != '1'))
          parse_fail(name, 0, "expected a 0/1 pixel");
        v = b[pos++] - '0';
      } else if (!to_int64(token(), v) || v < 0 || v > maxv) {
        parse_fail(name, 0, "bad pixel value at pixel " + std::to_string(i));
      }
      if (g.type == ScalarType::U16) {
        std::uint16_t x = std::uint16_t(v);
        std::memcpy(&g.data[i * 2], &x, 2);
      } else {
        g.data[i] = std::uint8_t(v);
      }
    }
    return g;
  }
  if (magic == "P4") {
    const std::int64_t row = (w + 7) / 8;
    if (pos + std::uint64_t(row * h) > b.size()) parse_fail(name, 0, "image body is truncated");
    g.data.resize(std::size_t(n));
    for (std::int64_t y = 0; y < h; ++y)
      for (std::int64_t x = 0; x < w; ++x)
        g.data[y * w + x] = (std::uint8_t(b[pos + y * row + x / 8]) >> (7 - x % 8)) & 1;
    return g;
  }
  const std::size_t bytes = std::size_t(n) * scalar_size(g.type);
  if (pos + bytes > b.size()) parse_fail(name, 0, "image body is truncated");
  g.data.assign(b.begin() + pos, b.begin() + pos + bytes);
  if (g.type == ScalarType::U16)  // Netpbm stores 16-bit samples big-endian
    for (std::size_t i = 0; i < bytes; i += 2) std::swap(g.data[i], g.data[i + 1]);
  return g;
}

struct PngSource {
  const std::string* b;
  std::size_t pos;
};
[[noreturn]] void png_error_fn(png_structp p, png_const_charp msg) {
  *static_cast<std::string*>(png_get_error_ptr(p)) = msg;
  png_longjmp(p, 1);
}
void png_warn_fn(png_structp, png_const_charp) {}

Grid parse_png(const std::string& b, const std::string& name) {
  if (b.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(b.data()), 0, 8) != 0)
    parse_fail(name, 0, "not a PNG file (bad signature)");
  std::string err;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &err, png_error_fn, png_warn_fn);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw Error(ErrorCode::OutOfMemory, "cannot create a PNG reader");
  PngSource src{&b, 0};
  Grid g;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    parse_fail(name, 0, "invalid PNG: " + err);
  }
  png_set_read_fn(png, &src, [](png_structp p, png_bytep out, png_size_t n) {
    auto* s = static_cast<PngSource*>(png_get_io_ptr(p));
    if (s->pos + n > s->b->size()) png_error(p, "file is truncated");
    std::memcpy(out, s->b->data() + s->pos, n);
    s->pos += n;
  });
  png_set_user_limits(png, 1 << 20, 1 << 20);
  png_read_info(png, info);
  png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  int depth = png_get_bit_depth(png, info), ct = png_get_color_type(png, info);
  if (ct == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (ct == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (ct & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
  if (ct == PNG_COLOR_TYPE_RGB || ct == PNG_COLOR_TYPE_RGB_ALPHA || ct == PNG_COLOR_TYPE_PALETTE)
    png_set_rgb_to_gray_fixed(png, 1, -1, -1);  // ITU-R 709 luminance
  if (depth == 16) png_set_swap(png);           // to little-endian samples
  png_read_update_info(png, info);
  const std::size_t rb = png_get_rowbytes(png, info);
  if (std::uint64_t(w) * h > (std::uint64_t(1) << 32)) png_error(png, "image too large");
  g.shape = {std::int64_t(h), std::int64_t(w)};
  g.type = depth == 16 ? ScalarType::U16 : ScalarType::U8;
  if (rb != std::size_t(w) * scalar_size(g.type)) png_error(png, "unexpected row layout");
  g.data.resize(rb * h);
  rows.resize(h);
  for (png_uint_32 y = 0; y < h; ++y) rows[y] = g.data.data() + y * rb;
  png_read_image(png, rows.data());
  png_destroy_read_struct(&png, &info, nullptr);
  return g;
}

// rgb: the grid holds rows x (3 * cols) bytes of RGB triples.
std::string format_png(const Grid& g, bool rgb = false) {
  if (g.shape.size() != 2 ||
      (g.type != ScalarType::U8 && g.type != ScalarType::U16 && g.type != ScalarType::Bool))
    throw Error(ErrorCode::InvalidArgument, "PNG output needs a 2D uint8, uint16 or bool grid");
  const int channels = rgb ? 3 : 1;
  std::string out, err;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &err, png_error_fn, png_warn_fn);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw Error(ErrorCode::OutOfMemory, "cannot create a PNG writer");
  std::vector<unsigned char> tmp;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw Error(ErrorCode::Io, "PNG encoding failed: " + err);
  }
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep d, png_size_t n) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<char*>(d), n);
      },
      nullptr);
  const int depth = g.type == ScalarType::U16 ? 16 : 8;
  png_set_IHDR(png, info, png_uint_32(g.shape[1] / channels), png_uint_32(g.shape[0]), depth,
               rgb ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (depth == 16) png_set_swap(png);
  const std::size_t rb = std::size_t(g.shape[1]) * (depth / 8);
  tmp = g.data;
  if (g.type == ScalarType::Bool)
    for (auto& v : tmp) v = v ? 255 : 0;
  for (std::int64_t y = 0; y < g.shape[0]; ++y) png_write_row(png, tmp.data() + y * rb);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

Grid parse_npy_grid(const std::string& b, const std::string& name) {
  NpyArray a = parse_npy(b, name);
  check_shape(a.shape, name);
  Grid g;
  g.shape = a.shape;
  const char k = a.descr[1];
  const std::size_t sz = npy_item_size(a.descr, name);
  if (k == 'b')
    g.type = ScalarType::Bool;
  else if (k == 'f')
    g.type = sz == 4 ? ScalarType::F32 : ScalarType::F64;
  else if (k == 'u' && sz == 1)
    g.type = ScalarType::U8;
  else if (k == 'u' && sz == 2)
    g.type = ScalarType::U16;
  else if (sz <= 4 && !(k == 'u' && sz == 4))
    g.type = ScalarType::I32;
  else
    g.type = ScalarType::I64;
  const std::int64_t n = g.count();
  g.data.resize(std::size_t(n) * scalar_size(g.type));
  // Same size and byte order: copy as is (uint64 goes the checked way, into int64).
  if (npy_item_size(a.descr, name) == scalar_size(g.type) && a.descr[0] != '>' &&
      !(k == 'u' && sz == 8)) {
    std::memcpy(g.data.data(), a.payload.data(), g.data.size());
    return g;
  }
  for (std::int64_t i = 0; i < n; ++i) {  // widen (int8/int16/uint32...) or byte-swap
    unsigned char* p = g.data.data() + i * scalar_size(g.type);
    if (g.type == ScalarType::F32 || g.type == ScalarType::F64) {
      const double v = npy_value(a, i, name);
      if (g.type == ScalarType::F32) {
        const float x = float(v);
        std::memcpy(p, &x, 4);
      } else {
        std::memcpy(p, &v, 8);
      }
      continue;
    }
    const std::int64_t v = npy_integer(a, i, name);  // integers never pass through a double
    if (g.type == ScalarType::I32) {
      const std::int32_t x = std::int32_t(v);  // only int8/int16/int32/uint8/uint16 map here
      std::memcpy(p, &x, 4);
    } else if (g.type == ScalarType::I64) {
      std::memcpy(p, &v, 8);
    } else if (g.type == ScalarType::U16) {
      const std::uint16_t x = std::uint16_t(v);
      std::memcpy(p, &x, 2);
    } else {
      p[0] = std::uint8_t(v);
    }
  }
  return g;
}

}  // namespace

Grid parse_grid(const std::string& b, const std::string& ext, const std::string& name) {
  if (ext == ".pgm" || ext == ".pbm" || ext == ".pnm") return parse_pnm(b, name);
  if (ext == ".png") return parse_png(b, name);
  if (ext == ".npy") return parse_npy_grid(b, name);
  throw Error(ErrorCode::InvalidArgument,
              name + ": unknown grid format '" + ext +
                  "': expected .png .pgm .pbm or .npy (raw files need --shape and --dtype)");
}

Grid read_grid(const std::string& path) {
  return parse_grid(read_file(path), extension(path), path);
}

Grid read_raw_grid(const std::string& path, const std::vector<std::int64_t>& shape, ScalarType t) {
  check_shape(shape, path);
  Grid g;
  g.shape = shape;
  g.type = t;
  std::string b = read_file(path);
  const std::uint64_t want = std::uint64_t(g.count()) * scalar_size(t);
  if (b.size() != want)
    throw Error(ErrorCode::Parse, path + ": raw file has " + std::to_string(b.size()) +
                                      " bytes, but the given shape and type need " +
                                      std::to_string(want));
  g.data.assign(b.begin(), b.end());
  return g;
}

void write_png_rgb(const std::string& path, std::int64_t rows, std::int64_t cols,
                   const std::vector<unsigned char>& rgb) {
  if (rows <= 0 || cols <= 0 || rgb.size() != std::size_t(rows * cols * 3))
    throw Error(ErrorCode::InvalidArgument, "RGB image data does not match its size");
  Grid g;  // rows x (3 * cols) bytes, written as RGB
  g.shape = {rows, cols * 3};
  g.type = ScalarType::U8;
  g.data = rgb;
  write_file_atomic(path, format_png(g, true));
}

void write_text(const std::string& path, const std::string& text) {
  write_file_atomic(path, text);
}

void write_grid(const std::string& path, const Grid& g) {
  const std::string ext = extension(path);
  if (ext != ".npy" && ext != ".raw") check_shape(g.shape, path);  // .npy takes any rank
  if (g.shape.empty())
    throw Error(ErrorCode::InvalidArgument, "a grid needs at least one dimension");
  if (g.data.size() != std::size_t(g.count()) * scalar_size(g.type))
    throw Error(ErrorCode::InvalidArgument, "grid data size does not match its shape");
  std::string out;
  if (ext == ".npy") {
    out = format_npy(scalar_info(g.type).npy_descr, g.shape, g.data.data(), g.data.size());
  } else if (ext == ".png") {
    out = format_png(g);
  } else if (ext == ".pgm" || ext == ".pbm") {
    if (g.shape.size() != 2) throw Error(ErrorCode::InvalidArgument, ext + " holds 2D images only");
    const std::int64_t h = g.shape[0], w = g.shape[1];
    if (ext == ".pbm") {
      out = "P4\n" + std::to_string(w) + " " + std::to_string(h) + "\n";
      const std::int64_t row = (w + 7) / 8;
      std::string body(std::size_t(row * h), '\0');
      for (std::int64_t y = 0; y < h; ++y)
        for (std::int64_t x = 0; x < w; ++x)
          if (g.value(y * w + x) != 0) body[y * row + x / 8] |= char(0x80 >> (x % 8));
      out += body;
    } else {
      if (g.type != ScalarType::U8 && g.type != ScalarType::U16)
        throw Error(ErrorCode::InvalidArgument, "PGM output needs a uint8 or uint16 grid");
      const bool wide = g.type == ScalarType::U16;
      out = "P5\n" + std::to_string(w) + " " + std::to_string(h) + "\n" +
            (wide ? "65535\n" : "255\n");
      std::string body(g.data.begin(), g.data.end());
      if (wide)
        for (std::size_t i = 0; i < body.size(); i += 2) std::swap(body[i], body[i + 1]);
      out += body;
    }
  } else if (ext == ".raw") {
    out.assign(g.data.begin(), g.data.end());
  } else {
    throw Error(ErrorCode::InvalidArgument,
                path + ": unknown grid format '" + ext + "': expected .png .pgm .pbm .npy or .raw");
  }
  write_file_atomic(path, out);
}

GridView view_of(const Grid& g) {
  const std::int64_t need = g.count() * std::int64_t(io::scalar_size(g.type));
  if (std::int64_t(g.data.size()) != need)
    throw Error(ErrorCode::InvalidArgument, "the grid holds " + std::to_string(g.data.size()) +
                                                " bytes; its shape and type need " +
                                                std::to_string(need));
  GridView v;
  v.data = g.data.data();
  v.type = g.type;
  v.shape = g.shape;
  return v;
}

}  // namespace gpugeom::io
