// The NumPy .npy container (format versions 1-3, C order).
#include <climits>
#include <cstdint>
#include <cstring>

#include "io/io_util.hpp"

namespace gpugeom::io::detail {
namespace {

bool host_little() {
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

std::string field(const std::string& h, const std::string& key, const std::string& name) {
  std::size_t k = h.find("'" + key + "'");
  if (k == std::string::npos) parse_fail(name, 0, "npy header has no '" + key + "' entry");
  std::size_t c = h.find(':', k);
  if (c == std::string::npos) parse_fail(name, 0, "npy header entry '" + key + "' has no value");
  return h.substr(c + 1);
}

}  // namespace

std::size_t npy_item_size(const std::string& d, const std::string& name) {
  if (d.size() < 3) parse_fail(name, 0, "unsupported npy dtype '" + d + "'");
  char kind = d[1];
  std::int64_t sz = 0;
  if (!to_int64(std::string_view(d).substr(2), sz) ||
      !((kind == 'f' && (sz == 4 || sz == 8)) ||
        ((kind == 'i' || kind == 'u') && (sz == 1 || sz == 2 || sz == 4 || sz == 8)) ||
        (kind == 'b' && sz == 1)))
    parse_fail(
        name, 0,
        "unsupported npy dtype '" + d + "': expected bool, (u)int8/16/32/64, float32 or float64");
  if (d[0] != '<' && d[0] != '>' && d[0] != '|' && d[0] != '=')
    parse_fail(name, 0, "npy dtype '" + d + "' has an unknown byte-order mark");
  return std::size_t(sz);
}

NpyArray parse_npy(std::string_view b, const std::string& name) {
  if (b.size() < 10 || std::memcmp(b.data(), "\x93NUMPY", 6) != 0)
    parse_fail(name, 0, "not an .npy file (missing the \\x93NUMPY magic)");
  const int major = (unsigned char)b[6];
  std::size_t hlen, start;
  if (major == 1) {
    hlen = (unsigned char)b[8] | (std::size_t((unsigned char)b[9]) << 8);
    start = 10;
  } else if (major == 2 || major == 3) {
    if (b.size() < 12) parse_fail(name, 0, "truncated .npy header");
    hlen = 0;
    for (int i = 0; i < 4; ++i) hlen |= std::size_t((unsigned char)b[8 + i]) << (8 * i);
    start = 12;
  } else {
    parse_fail(name, 0, "unsupported .npy format version " + std::to_string(major));
  }
  if (hlen > b.size() - start) parse_fail(name, 0, "truncated .npy header");
  const std::string h(b.substr(start, hlen));
  NpyArray a;
  std::string d = field(h, "descr", name);
  std::size_t q1 = d.find('\''), q2 = q1 == std::string::npos ? q1 : d.find('\'', q1 + 1);
  if (q2 == std::string::npos) parse_fail(name, 0, "npy 'descr' is not a quoted dtype string");
  a.descr = d.substr(q1 + 1, q2 - q1 - 1);
  std::string fo = field(h, "fortran_order", name);
  if (fo.find("True") < fo.find_first_of(",}"))
    parse_fail(name, 0,
               "Fortran-ordered arrays are not supported: save with np.ascontiguousarray(a)");
  std::string s = field(h, "shape", name);
  std::size_t lp = s.find('('), rp = s.find(')');
  if (lp == std::string::npos || rp == std::string::npos || rp < lp)
    parse_fail(name, 0, "npy 'shape' is not a tuple");
  for (auto tok : split(std::string_view(s).substr(lp + 1, rp - lp - 1), true)) {
    std::int64_t v;
    if (!to_int64(tok, v) || v < 0)
      parse_fail(name, 0, "bad npy shape entry '" + std::string(tok) + "'");
    a.shape.push_back(v);
  }
  const std::size_t item = npy_item_size(a.descr, name);
  unsigned __int128 total = item;
  for (auto v : a.shape) total *= (unsigned __int128)v;
  const std::size_t avail = b.size() - start - hlen;
  if (total > avail)
    parse_fail(name, 0,
               "npy payload is truncated: the header promises " +
                   std::to_string((unsigned long long)total) + " bytes, the file has " +
                   std::to_string(avail));
  a.payload = std::string_view(b).substr(start + hlen, std::size_t(total));
  return a;
}

std::int64_t npy_integer(const NpyArray& a, std::int64_t i, const std::string& name) {
  const std::size_t sz = npy_item_size(a.descr, name);
  unsigned char raw[8];
  std::memcpy(raw, a.payload.data() + std::size_t(i) * sz, sz);
  const bool little =
      a.descr[0] == '<' || ((a.descr[0] == '=' || a.descr[0] == '|') && host_little());
  std::uint64_t u = 0;  // assemble the value from its bytes, in the file's byte order
  for (std::size_t k = 0; k < sz; ++k) u |= std::uint64_t(raw[little ? k : sz - 1 - k]) << (8 * k);
  if (a.descr[1] == 'i' && sz < 8 && (u >> (8 * sz - 1)) & 1)
    u |= ~std::uint64_t(0) << (8 * sz);  // sign
  if (a.descr[1] == 'b') return u != 0;
  if (a.descr[1] == 'u' && sz == 8 && u > std::uint64_t(INT64_MAX))
    parse_fail(name, 0, "uint64 value " + std::to_string(u) + " is above the supported 2^63-1");
  return std::int64_t(u);
}

double npy_value(const NpyArray& a, std::int64_t i, const std::string& name) {
  const std::size_t sz = npy_item_size(a.descr, name);
  if (a.descr[1] != 'f') return double(npy_integer(a, i, name));
  unsigned char raw[8];
  std::memcpy(raw, a.payload.data() + std::size_t(i) * sz, sz);
  const bool little =
      a.descr[0] == '<' || ((a.descr[0] == '=' || a.descr[0] == '|') && host_little());
  if (little != host_little())
    for (std::size_t k = 0; k < sz / 2; ++k) std::swap(raw[k], raw[sz - 1 - k]);
  if (sz == 4) {
    float f;
    std::memcpy(&f, raw, 4);
    return f;
  }
  double d;
  std::memcpy(&d, raw, 8);
  return d;
}

std::string format_npy(const std::string& descr, const std::vector<std::int64_t>& shape,
                       const void* data, std::size_t bytes) {
  std::string h = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (";
  for (std::size_t i = 0; i < shape.size(); ++i) h += std::to_string(shape[i]) + ", ";
  if (shape.size() > 1) h.resize(h.size() - 1), h.back() = ' ', h.pop_back();
  if (shape.size() == 1) h.pop_back();  // "(5,)" keeps its comma
  h += "), }";
  const std::size_t total = 10 + h.size() + 1;
  h.append((64 - total % 64) % 64, ' ');
  h += '\n';
  std::string out = "\x93NUMPY";
  out += char(1);
  out += char(0);
  out += char(h.size() & 0xff);
  out += char(h.size() >> 8);
  out += h;
  out.append(static_cast<const char*>(data), bytes);
  return out;
}

}  // namespace gpugeom::io::detail
