// VTK XML unstructured grids (.vtu), as ParaView and VTK write them: the reader.
// (The writer is vtu_write.cpp.)
// Read: every DataArray encoding VTK defines: ascii, inline base64 ("binary"), appended raw
// or base64; uncompressed or vtkZLibDataCompressor; header_type UInt32 or UInt64; little or
// big endian; any numeric element type. Interpreted: what a triangle or tetrahedron mesh needs
// (Points, connectivity, offsets, types) and the PointData / CellData arrays (kept with their
// names and types, written the same ways); other sections are skipped.
//
// Every size read from a file is checked against the bytes that are there before it is used,
// so a malformed or hostile file is a Parse error, never a huge allocation or a read past the
// end.
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gpugeom/io.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io::detail {
namespace {

// ---- base64 (RFC 4648) ----

constexpr char kB64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int b64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// The base64 characters of s, whitespace removed.
std::string b64_chars(std::string_view s) {
  std::string c;
  c.reserve(s.size());
  for (char x : s)
    if (x != ' ' && x != '\n' && x != '\r' && x != '\t') c += x;
  return c;
}

// Decodes whole 4-character groups of c (padding allowed in a group's last two places).
std::string b64_decode(std::string_view c, const std::string& name) {
  if (c.size() % 4) parse_fail(name, 0, "base64 data whose length is not a multiple of 4");
  std::string out;
  out.reserve(c.size() / 4 * 3);
  for (std::size_t i = 0; i < c.size(); i += 4) {
    int v[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      if (c[i + k] == '=' && k >= 2) {
        v[k] = 0;
        ++pad;
        continue;
      }
      v[k] = b64_value(c[i + k]);
      if (v[k] < 0 || pad) parse_fail(name, 0, "a character that is not base64 in binary data");
    }
    const std::uint32_t w = (v[0] << 18) | (v[1] << 12) | (v[2] << 6) | v[3];
    out += char(w >> 16);
    if (pad < 2) out += char((w >> 8) & 0xFF);
    if (pad < 1) out += char(w & 0xFF);
  }
  return out;
}

// ---- a small XML scanner: tags and their attributes (no entities, no nesting rules) ----

struct Tag {
  std::string_view name;
  std::string_view attrs;  // between the name and '>' or '/>'
  std::size_t begin = 0;   // '<'
  std::size_t end = 0;     // one past '>'
  bool closed = false;     // "/>"
};

// The next tag named `name` at or after `from`, or none.
bool find_tag(std::string_view b, std::string_view name, std::size_t from, Tag& t) {
  for (std::size_t k = b.find('<', from); k != std::string_view::npos; k = b.find('<', k + 1)) {
    if (b.compare(k + 1, name.size(), name) != 0) continue;
    const std::size_t after = k + 1 + name.size();
    if (after >= b.size() || !(b[after] == ' ' || b[after] == '>' || b[after] == '/' ||
                               b[after] == '\n' || b[after] == '\r' || b[after] == '\t'))
      continue;
    const std::size_t gt = b.find('>', after);
    if (gt == std::string_view::npos) return false;
    t.name = b.substr(k + 1, name.size());
    t.closed = gt > after && b[gt - 1] == '/';
    t.attrs = b.substr(after, gt - after - (t.closed ? 1 : 0));
    t.begin = k;
    t.end = gt + 1;
    return true;
  }
  return false;
}

// The value of attribute `key` (key="value" or key='value'), or empty.
std::string_view attr(const Tag& t, std::string_view key) {
  const std::string_view a = t.attrs;
  for (std::size_t k = a.find(key); k != std::string_view::npos; k = a.find(key, k + 1)) {
    if (k > 0 && !(a[k - 1] == ' ' || a[k - 1] == '\n' || a[k - 1] == '\t' || a[k - 1] == '\r'))
      continue;
    std::size_t e = k + key.size();
    while (e < a.size() && a[e] == ' ') ++e;
    if (e >= a.size() || a[e] != '=') continue;
    ++e;
    while (e < a.size() && a[e] == ' ') ++e;
    if (e >= a.size() || (a[e] != '"' && a[e] != '\'')) continue;
    const std::size_t close = a.find(a[e], e + 1);
    if (close == std::string_view::npos) return {};
    return a.substr(e + 1, close - e - 1);
  }
  return {};
}

// ---- element types ----

using Elem = NumType;
Elem elem_of(std::string_view type, const std::string& name) {
  static const struct {
    const char* n;
    Elem e;
  } kTypes[] = {
      {"Int8", {1, 'i'}},    {"UInt8", {1, 'u'}},   {"Int16", {2, 'i'}}, {"UInt16", {2, 'u'}},
      {"Int32", {4, 'i'}},   {"UInt32", {4, 'u'}},  {"Int64", {8, 'i'}}, {"UInt64", {8, 'u'}},
      {"Float32", {4, 'f'}}, {"Float64", {8, 'f'}}, {"Char", {1, 'i'}},  {"UChar", {1, 'u'}},
      {"Short", {2, 'i'}},   {"UShort", {2, 'u'}},  {"Int", {4, 'i'}},   {"UInt", {4, 'u'}},
      {"Long", {8, 'i'}},    {"ULong", {8, 'u'}},   {"Float", {4, 'f'}}, {"Double", {8, 'f'}}};
  for (const auto& t : kTypes)
    if (type == t.n) return t.e;
  parse_fail(name, 0, "unsupported DataArray type '" + std::string(type) + "'");
}

// n elements of raw bytes as doubles, on all host threads for large arrays.
void elem_values(const unsigned char* p, std::size_t n, const Elem& e, bool big, double* out) {
  visit_num(e, [&](auto zero) {
    using T = decltype(zero);
#pragma omp parallel for schedule(static) if (n > (std::size_t(1) << 16))
    for (std::int64_t i = 0; i < std::int64_t(n); ++i)
      out[i] = double(num_at<T>(p, std::size_t(i), big));
  });
}

// ---- the file's encoding settings ----

struct Encoding {
  bool big = false;            // byte_order="BigEndian"
  int header = 4;              // header_type UInt32 (VTK's default) or UInt64
  bool zlib = false;           // compressor="vtkZLibDataCompressor"
  std::string_view appended;   // the appended data after '_', raw or decoded base64
  std::string appended_store;  // (owns decoded base64 appended data)
  bool appended_base64 = false;
  std::string name;
};

std::uint64_t header_word(const Encoding& E, const unsigned char* p) {
  unsigned char b[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int k = 0; k < E.header; ++k) b[k] = E.big ? p[E.header - 1 - k] : p[k];
  std::uint64_t v;
  std::memcpy(&v, b, 8);
  return v;
}

// The length of a block's header (in bytes) given its first words, or 0 if more are needed.
std::size_t header_bytes(const Encoding& E, std::uint64_t first_word) {
  if (!E.zlib) return std::size_t(E.header);
  return std::size_t(E.header) * std::size_t(3 + first_word);
}

// The data of one array from bytes that start with its header (uncompressed: the byte count;
// zlib: block count, block size, last block size, compressed sizes). `avail`: bytes there.
// Returns the uncompressed bytes; `used` the bytes consumed.
std::string block_data(const Encoding& E, const unsigned char* p, std::size_t avail,
                       std::size_t& used) {
  const std::string& name = E.name;
  auto need = [&](std::size_t n) {
    if (n > avail) parse_fail(name, 0, "binary data ends before its header says");
  };
  need(std::size_t(E.header));
  if (!E.zlib) {
    const std::uint64_t n = header_word(E, p);
    if (n > avail - std::size_t(E.header))
      parse_fail(name, 0, "binary data ends before its header says");
    used = std::size_t(E.header) + std::size_t(n);
    return std::string(reinterpret_cast<const char*>(p) + E.header, std::size_t(n));
  }
  need(3 * std::size_t(E.header));
  const std::uint64_t nb = header_word(E, p), bs = header_word(E, p + E.header),
                      last = header_word(E, p + 2 * E.header);
  if (nb > avail / std::size_t(E.header))
    parse_fail(name, 0, "compressed block count out of range");
  const std::size_t hb = header_bytes(E, nb);
  need(hb);
  if (nb > 0 && (bs == 0 || last > bs)) parse_fail(name, 0, "bad compressed block sizes");
  std::uint64_t total_c = 0;  // (each size checked before adding: no wrap-around)
  for (std::uint64_t i = 0; i < nb; ++i) {
    const std::uint64_t c = header_word(E, p + (3 + i) * E.header);
    if (c > avail - hb - total_c)
      parse_fail(name, 0, "compressed data ends before its header says");
    total_c += c;
  }
  // zlib expands at most about 1032 : 1; a larger claim is a broken header.
  const std::uint64_t cap = (total_c + 64) * 1100;
  if (nb > 1 && (bs > cap || nb - 1 > cap / bs))
    parse_fail(name, 0, "compressed block sizes out of range");
  const std::uint64_t total_u = nb == 0 ? 0 : (nb - 1) * bs + (last ? last : bs);
  if (total_u > cap) parse_fail(name, 0, "compressed block sizes out of range");
  // The blocks are independent: each decompressed on its own thread, from its offset in the
  // compressed data into its place in the output.
  std::vector<std::size_t> from(std::size_t(nb) + 1, hb);
  for (std::uint64_t i = 0; i < nb; ++i)
    from[std::size_t(i) + 1] = from[std::size_t(i)] + header_word(E, p + (3 + i) * E.header);
  std::string out(std::size_t(total_u), '\0');
  std::int64_t bad = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : bad) if (nb > 1)
  for (std::int64_t i = 0; i < std::int64_t(nb); ++i) {
    const std::size_t b = std::size_t(i);
    const uLongf expect = uLongf(b + 1 < nb || last == 0 ? bs : last);
    uLongf want = expect;
    if (uncompress(reinterpret_cast<Bytef*>(&out[b * std::size_t(bs)]), &want, p + from[b],
                   uLong(from[b + 1] - from[b])) != Z_OK ||
        want != expect)
      ++bad;
  }
  if (bad) parse_fail(name, 0, "a zlib block does not decompress to its stated size");
  used = from[std::size_t(nb)];
  return out;
}

// Inline base64 ("binary"): the header and the data may have been encoded together or apart
// (VTK encodes them apart; other writers together). Apart, the header's own group ends in
// '=' padding unless its length is a multiple of 3, in which case both readings agree.
std::string inline_data(const Encoding& E, std::string_view text) {
  const std::string c = b64_chars(text);
  const std::string& name = E.name;
  // the first words tell the header's length
  const std::size_t first = E.zlib ? 3 * std::size_t(E.header) : std::size_t(E.header);
  const std::size_t first_chars = (first + 2) / 3 * 4;
  if (c.size() < first_chars) parse_fail(name, 0, "binary data shorter than its header");
  const std::string head = b64_decode(std::string_view(c).substr(0, first_chars), name);
  if (head.size() < first) parse_fail(name, 0, "binary data shorter than its header");
  const std::uint64_t w0 = header_word(E, reinterpret_cast<const unsigned char*>(head.data()));
  if (E.zlib && w0 > c.size()) parse_fail(name, 0, "compressed block count out of range");
  const std::size_t hb = header_bytes(E, w0), hchars = (hb + 2) / 3 * 4;
  if (c.size() < hchars) parse_fail(name, 0, "binary data shorter than its header");
  const bool apart = c.compare(hchars - 1, 1, "=") == 0;
  std::string bytes;
  if (apart) {
    bytes = b64_decode(std::string_view(c).substr(0, hchars), name);
    bytes.resize(hb);  // (padding)
    bytes += b64_decode(std::string_view(c).substr(hchars), name);
  } else {
    bytes = b64_decode(c, name);
  }
  std::size_t used = 0;
  return block_data(E, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), used);
}

// One DataArray's values as doubles (exact for every integer below 2^53 and every float).
// The decoded bytes (file byte order) and element type of a binary DataArray (inline base64 or
// appended raw; appended base64 is the caller's); false, with nothing read, for ascii.
bool array_bytes(const Encoding& E, std::string_view b, const Tag& t, std::string& bytes, Elem& e) {
  const std::string& name = E.name;
  e = elem_of(attr(t, "type"), name);
  const std::string_view format = attr(t, "format");
  if (format == "ascii") return false;
  if (format == "binary") {
    if (t.closed) parse_fail(name, 0, "an inline binary DataArray without data");
    const std::size_t close = b.find("</DataArray>", t.end);
    if (close == std::string_view::npos) parse_fail(name, 0, "a DataArray is not closed");
    bytes = inline_data(E, b.substr(t.end, close - t.end));
  } else if (format == "appended") {
    std::int64_t off = 0;
    if (!to_int64(attr(t, "offset"), off) || off < 0 || std::uint64_t(off) > E.appended.size())
      parse_fail(name, 0, "an appended DataArray's offset is missing or out of range");
    std::size_t used = 0;
    bytes = block_data(E, reinterpret_cast<const unsigned char*>(E.appended.data()) + off,
                       E.appended.size() - std::size_t(off), used);
  } else {
    parse_fail(name, 0, "unknown DataArray format '" + std::string(format) + "'");
  }
  if (bytes.size() % std::size_t(e.bytes))
    parse_fail(name, 0, "binary DataArray length is not a whole number of elements");
  return true;
}

// One DataArray's values as doubles (exact for every integer below 2^53 and every float).
std::vector<double> read_array(const Encoding& E, std::string_view b, const Tag& t) {
  std::vector<double> v;
  std::string bytes;
  Elem e;
  if (array_bytes(E, b, t, bytes, e)) {
    v.resize(bytes.size() / std::size_t(e.bytes));
    elem_values(reinterpret_cast<const unsigned char*>(bytes.data()), v.size(), e, E.big, v.data());
    return v;
  }
  if (t.closed) return v;
  const std::size_t close = b.find("</DataArray>", t.end);
  if (close == std::string_view::npos) parse_fail(E.name, 0, "a DataArray is not closed");
  const std::string_view text = b.substr(t.end, close - t.end);
  std::string_view s;
  for (std::size_t pos = 0; next_token(text, pos, s);) {
    double x;
    if (!to_double(s, x))
      parse_fail(E.name, 0, "bad number '" + std::string(s) + "' in a DataArray");
    v.push_back(x);
  }
  return v;
}

// The ScalarType a VTK type is read as, and the values stored in it.
DataArray data_array_of(const std::string& name, const std::string& file, std::string_view vtk_type,
                        int comps, const std::vector<double>& v) {
  ScalarType t = ScalarType::F64;
  if (vtk_type == "UInt8")
    t = ScalarType::U8;
  else if (vtk_type == "UInt16")
    t = ScalarType::U16;
  else if (vtk_type == "Int8" || vtk_type == "Int16" || vtk_type == "Int32")
    t = ScalarType::I32;
  else if (vtk_type == "UInt32" || vtk_type == "Int64" || vtk_type == "UInt64")
    t = ScalarType::I64;
  else if (vtk_type == "Float32")
    t = ScalarType::F32;
  DataArray a;
  if (!data_array_from(name, t, comps, v, a))
    parse_fail(file, 0, "array '" + name + "' holds a value outside the range of its type");
  return a;
}

}  // namespace

Mesh parse_vtu(std::string_view bytes, const std::string& name) {
  // The XML part ends where appended data begins (raw bytes may hold anything after it).
  std::string_view all(bytes);
  Tag file, grid, app;
  if (!find_tag(all, "VTKFile", 0, file) || attr(file, "type") != "UnstructuredGrid" ||
      !find_tag(all, "UnstructuredGrid", file.end, grid))
    parse_fail(name, 0, "not a VTK UnstructuredGrid (.vtu) file");
  Encoding E;
  E.name = name;
  const std::string_view order = attr(file, "byte_order"), ht = attr(file, "header_type"),
                         comp = attr(file, "compressor");
  E.big = order == "BigEndian";
  if (!order.empty() && order != "BigEndian" && order != "LittleEndian")
    parse_fail(name, 0, "unknown byte_order '" + std::string(order) + "'");
  if (ht == "UInt64")
    E.header = 8;
  else if (ht.empty() || ht == "UInt32")
    E.header = 4;
  else
    parse_fail(name, 0, "unsupported header_type '" + std::string(ht) + "'");
  if (comp == "vtkZLibDataCompressor")
    E.zlib = true;
  else if (!comp.empty())
    parse_fail(name, 0, "unsupported compressor '" + std::string(comp) + "' (zlib is read)");
  std::string_view xml = all;
  if (find_tag(all, "AppendedData", grid.end, app)) {
    const std::string_view enc = attr(app, "encoding");
    const std::size_t us = all.find('_', app.end);
    if (us == std::string_view::npos) parse_fail(name, 0, "<AppendedData> without its '_' marker");
    xml = all.substr(0, app.begin);
    if (enc == "base64") {
      const std::size_t close = all.find("</AppendedData>", us);
      E.appended_store = b64_chars(all.substr(
          us + 1, close == std::string_view::npos ? std::string_view::npos : close - us - 1));
      E.appended_base64 = true;
      E.appended = E.appended_store;
    } else if (enc == "raw" || enc.empty()) {
      E.appended = all.substr(us + 1);
    } else {
      parse_fail(name, 0, "unknown AppendedData encoding '" + std::string(enc) + "'");
    }
  }
  // One DataArray's values. Appended base64: each array's block is its own base64 text from
  // its offset (in characters); decoding from there on gives its bytes first.
  auto read_one = [&](const Tag& t) -> std::vector<double> {
    if (!E.appended_base64 || attr(t, "format") != "appended") return read_array(E, xml, t);
    std::int64_t off = 0;
    if (!to_int64(attr(t, "offset"), off) || off < 0 || std::uint64_t(off) > E.appended.size())
      parse_fail(name, 0, "an appended DataArray's offset is missing or out of range");
    const std::string_view rest = E.appended.substr(std::size_t(off));
    const std::string data = inline_data(E, rest.substr(0, rest.size() / 4 * 4));
    const Elem e = elem_of(attr(t, "type"), name);
    if (data.size() % std::size_t(e.bytes))
      parse_fail(name, 0, "binary DataArray length is not a whole number of elements");
    std::vector<double> v(data.size() / std::size_t(e.bytes));
    elem_values(reinterpret_cast<const unsigned char*>(data.data()), v.size(), e, E.big, v.data());
    return v;
  };
  // Calls f(tag) for each DataArray of the section (none when the section is absent and
  // optional).
  auto each_array = [&](std::string_view section, bool required, auto f) {
    Tag sec, t;
    if (!find_tag(xml, section, 0, sec)) {
      if (required) parse_fail(name, 0, "no <" + std::string(section) + "> section");
      return;
    }
    if (sec.closed) return;
    const std::size_t end = xml.find("</" + std::string(section) + ">", sec.end);
    for (std::size_t at = sec.end;
         find_tag(xml, "DataArray", at, t) && (end == std::string_view::npos || t.begin < end);
         at = t.end)
      f(t);
  };
  // The DataArray named arr (the first, when arr is empty) of a section.
  auto find_array = [&](std::string_view section, std::string_view arr) {
    Tag found;
    bool any = false;
    each_array(section, true, [&](const Tag& t) {
      if (any || (!arr.empty() && attr(t, "Name") != arr)) return;
      found = t;
      any = true;
    });
    if (!any)
      parse_fail(name, 0,
                 "no DataArray " + (arr.empty() ? std::string() : "'" + std::string(arr) + "' ") +
                     "in <" + std::string(section) + ">");
    return found;
  };
  auto array = [&](std::string_view section, std::string_view arr) {
    return read_one(find_array(section, arr));
  };
  const std::vector<double> xyz = array("Points", "");
  // Connectivity in an integer type is converted straight to the cells (the bulk of a mesh
  // file); anything else goes through doubles like the other arrays.
  const Tag conn_tag = find_array("Cells", "connectivity");
  std::string conn_bytes;
  Elem conn_elem;
  const bool conn_raw = !(E.appended_base64 && attr(conn_tag, "format") == "appended") &&
                        array_bytes(E, xml, conn_tag, conn_bytes, conn_elem) &&
                        conn_elem.kind != 'f';
  const std::vector<double> conn = conn_raw ? std::vector<double>() : read_one(conn_tag);
  const std::size_t nconn =
      conn_raw ? conn_bytes.size() / std::size_t(conn_elem.bytes) : conn.size();
  const std::vector<double> offs = array("Cells", "offsets");
  const std::vector<double> types = array("Cells", "types");
  if (xyz.size() % 3) parse_fail(name, 0, "Points must have 3 components");
  if (offs.size() != types.size()) parse_fail(name, 0, "offsets and types differ in length");
  Mesh m;
  m.cell_size = types.empty() || types[0] == 5 ? 3 : 4;
  const std::size_t nv = xyz.size() / 3, nc = offs.size();
  const std::int64_t k = m.cell_size, want_type = k == 3 ? 5 : 10;
  // The checks and copies below run on all host threads, in the order (and with the messages)
  // of the serial loops they replace; each reports whether any item fails it.
  int bad_type = 0, bad_offset = 0, bad_vertex = 0, not_flat = 0;
#pragma omp parallel for schedule(static) reduction(max : bad_type) if (nc > 65536)
  for (std::int64_t i = 0; i < std::int64_t(nc); ++i)
    bad_type = std::max(bad_type, int(types[std::size_t(i)] != double(want_type)));
  if (bad_type)
    parse_fail(name, 0, "mixed or unsupported VTK cell types (expected all 5 or all 10)");
  if (nconn != nc * std::size_t(k))
    parse_fail(name, 0, "connectivity length does not match the cells");
#pragma omp parallel for schedule(static) reduction(max : bad_offset) if (nc > 65536)
  for (std::int64_t i = 0; i < std::int64_t(nc); ++i)
    bad_offset = std::max(bad_offset, int(offs[std::size_t(i)] != double((i + 1) * k)));
  if (bad_offset) parse_fail(name, 0, "unexpected offsets");
  m.cells.resize(nconn);
  if (conn_raw) {
    const auto* p = reinterpret_cast<const unsigned char*>(conn_bytes.data());
    const bool big = E.big;
    visit_num(conn_elem, [&](auto zero) {  // (an integer type: floats take the other branch)
      using T = decltype(zero);
#pragma omp parallel for schedule(static) reduction(max : bad_vertex) if (nconn > 65536)
      for (std::int64_t i = 0; i < std::int64_t(nconn); ++i) {
        const T v = num_at<T>(p, std::size_t(i), big);
        const bool ok = v >= T(0) && double(v) < double(nv);
        bad_vertex = std::max(bad_vertex, int(!ok));
        m.cells[std::size_t(i)] = ok ? std::int32_t(v) : 0;
      }
    });
  } else {
#pragma omp parallel for schedule(static) reduction(max : bad_vertex) if (nconn > 65536)
    for (std::int64_t i = 0; i < std::int64_t(nconn); ++i) {
      const double c = conn[std::size_t(i)];
      const bool ok = c >= 0 && c < double(nv);
      bad_vertex = std::max(bad_vertex, int(!ok));
      m.cells[std::size_t(i)] = ok ? std::int32_t(c) : 0;
    }
  }
  if (bad_vertex) parse_fail(name, 0, "connectivity refers to a missing point");
#pragma omp parallel for schedule(static) reduction(max : not_flat) if (nv > 65536)
  for (std::int64_t i = 0; i < std::int64_t(nv); ++i)
    not_flat = std::max(not_flat, int(xyz[3 * std::size_t(i) + 2] != 0.0));
  m.dim = (!not_flat && m.cell_size == 3) ? 2 : 3;
  m.coords.resize(nv * std::size_t(m.dim));
  const std::size_t dm = std::size_t(m.dim);
#pragma omp parallel for schedule(static) if (nv > 65536)
  for (std::int64_t i = 0; i < std::int64_t(nv); ++i)
    for (std::size_t d = 0; d < dm; ++d)
      m.coords[std::size_t(i) * dm + d] = xyz[3 * std::size_t(i) + d];
  // Point and cell data, each array in the type it was written in (where a ScalarType has it).
  auto data_section = [&](std::string_view section, std::size_t items,
                          std::vector<DataArray>& out) {
    each_array(section, false, [&](const Tag& t) {
      std::int64_t comps = 1;
      const std::string_view nc = attr(t, "NumberOfComponents");
      if (!nc.empty() && (!to_int64(nc, comps) || comps < 1 || comps > 1024))
        parse_fail(name, 0, "bad NumberOfComponents in <" + std::string(section) + ">");
      const std::vector<double> v = read_one(t);
      if (v.size() != items * std::size_t(comps))
        parse_fail(name, 0,
                   "<" + std::string(section) + "> array '" + std::string(attr(t, "Name")) +
                       "' holds " + std::to_string(v.size()) + " values, expected " +
                       std::to_string(items * std::size_t(comps)));
      out.push_back(
          data_array_of(std::string(attr(t, "Name")), name, attr(t, "type"), int(comps), v));
    });
  };
  data_section("PointData", nv, m.point_data);
  data_section("CellData", offs.size(), m.cell_data);
  return m;
}

}  // namespace gpugeom::io::detail
