#include "io/io_util.hpp"

#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <type_traits>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "exec/scalar_table.hpp"

namespace gpugeom::io::detail {

std::string sibling(const std::string& path, const std::string& ext) {
  std::size_t dot = path.find_last_of('.');
  return path.substr(0, dot) + ext;
}

std::string read_file(const std::string& path) {
  // One read into a string of the file's size (no stream buffer copy in between).
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f)
    throw Error(ErrorCode::Io, "cannot open '" + path + "' for reading: " + std::strerror(errno));
  std::string b;
  struct stat st;
  if (::fstat(::fileno(f), &st) == 0 && S_ISREG(st.st_mode)) b.resize(std::size_t(st.st_size));
  std::size_t got = b.empty() ? 0 : std::fread(&b[0], 1, b.size(), f);
  b.resize(got);
  // What fstat did not announce (a file that grew, a pipe): read on in blocks.
  char chunk[1 << 16];
  for (std::size_t k; (k = std::fread(chunk, 1, sizeof chunk, f)) > 0;) b.append(chunk, k);
  const bool bad = std::ferror(f) != 0;
  std::fclose(f);
  if (bad) throw Error(ErrorCode::Io, "error while reading '" + path + "'");
  return b;
}

FileView::FileView(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0)
    throw Error(ErrorCode::Io, "cannot open '" + path + "' for reading: " + std::strerror(errno));
  struct stat st;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    void* p = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
    if (p != MAP_FAILED) {
      map_ = static_cast<const char*>(p);
      size_ = std::size_t(st.st_size);
      (void)::madvise(p, size_, MADV_WILLNEED);  // read ahead while the first parts parse
    }
  }
  ::close(fd);
  if (!map_) copy_ = read_file(path);  // (pipes, empty files, systems that refuse to map)
}
FileView::~FileView() {
  if (map_) ::munmap(const_cast<char*>(map_), size_);
}

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
  std::random_device rd;
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, ".tmp-%d-%08x", int(getpid()), unsigned(rd()));
  tmp_ = path + suffix;
  f_ = std::fopen(tmp_.c_str(), "wb");
  if (!f_)
    throw Error(ErrorCode::Io,
                "cannot create '" + tmp_ + "' (writing '" + path + "'): " + std::strerror(errno));
}
AtomicFile::~AtomicFile() {
  if (f_) {
    std::fclose(f_);
    std::remove(tmp_.c_str());
  }
}
void AtomicFile::fail(int err) {
  if (f_) std::fclose(f_);
  f_ = nullptr;
  std::remove(tmp_.c_str());
  throw Error(ErrorCode::Io, "cannot write '" + path_ + "': " + std::strerror(err));
}
void AtomicFile::write(const void* data, std::size_t bytes) {
  if (bytes && std::fwrite(data, 1, bytes, f_) != bytes) fail(errno);
}
void AtomicFile::commit() {
  const bool ok = std::fflush(f_) == 0;
  const int e = errno;
  const bool closed = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok || !closed || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int err = ok && closed ? errno : e;
    std::remove(tmp_.c_str());
    throw Error(ErrorCode::Io, "cannot write '" + path_ + "': " + std::strerror(err));
  }
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
  AtomicFile f(path);
  f.write(bytes.data(), bytes.size());
  f.commit();
}
void write_file_atomic(const std::string& path, const Text& text) {
  AtomicFile f(path);
  for (const std::string& s : text.pieces()) f.write(s.data(), s.size());
  f.commit();
}

int host_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Counts the line ends of `text` and the lines Lines::next would return (not blank, not a
// '#' comment): a part's first line number and its first point.
void count_lines(std::string_view text, std::int64_t& ends, std::int64_t& data) {
  ends = data = 0;
  std::size_t i = 0;
  while (i < text.size()) {
    std::size_t e = text.find('\n', i);
    if (e == std::string_view::npos)
      e = text.size();
    else
      ++ends;
    std::size_t j = i;
    while (j < e && (text[j] == ' ' || text[j] == '\t' || text[j] == '\r')) ++j;
    data += j < e && text[j] != '#';
    i = e + 1;
  }
}

void parse_fail(const std::string& name, std::int64_t line, const std::string& what) {
  std::string where = name;
  if (line > 0) where += ":" + std::to_string(line);
  throw Error(ErrorCode::Parse, where + ": " + what);
}

bool Lines::next(std::string_view& line, bool skip_comments) {
  while (pos_ < t_.size()) {
    std::size_t e = t_.find('\n', pos_);
    if (e == std::string_view::npos) e = t_.size();
    line = t_.substr(pos_, e - pos_);
    pos_ = e + 1;
    ++line_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    // Any mix of spaces, tabs and stray carriage returns is a blank line (split() treats all
    // of them as separators, so a line kept here always has a first token).
    std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) continue;
    line = line.substr(first);
    if (skip_comments && line[0] == '#') continue;
    return true;
  }
  return false;
}

Tokens split(std::string_view line, bool commas) {
  Tokens out;
  std::string_view t;
  for (std::size_t pos = 0; next_token(line, pos, t, commas);) out.push(t);
  return out;
}

void Tokens::drop_front() {
  if (n_ == 0) return;
  if (n_ <= kInline) {
    std::copy(in_ + 1, in_ + n_, in_);
  } else {
    more_.erase(more_.begin());
    if (n_ - 1 == kInline) std::copy(more_.begin(), more_.end(), in_);  // back in place
  }
  --n_;
}

bool to_double(std::string_view s, double& v) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}
bool to_int64(std::string_view s, std::int64_t& v) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}
double need_double(const Lines& l, std::string_view s, const char* what) {
  double v;
  if (!to_double(s, v))
    l.fail(std::string("expected a number for ") + what + ", found '" + std::string(s) + "'");
  return v;
}
std::int64_t need_int(const Lines& l, std::string_view s, const char* what) {
  std::int64_t v;
  if (!to_int64(s, v))
    l.fail(std::string("expected an integer for ") + what + ", found '" + std::string(s) + "'");
  return v;
}

Text format_vertex_lines(const double* coords, int dim, std::size_t n, const char* prefix) {
  const std::size_t dm = std::size_t(dim);
  return format_lines(n, 80, [&](std::size_t i, std::string& o) {
    o += prefix;
    for (std::size_t d = 0; d < 3; ++d) {
      if (d) o += ' ';
      append_double(o, d < dm ? coords[i * dm + d] : 0.0);
    }
    o += '\n';
  });
}

Text format_cell_lines(const std::int32_t* cells, int k, std::size_t n, const char* lead,
                       bool number_cells, int base) {
  const std::size_t kk = std::size_t(k);
  return format_lines(n, 12 * kk + 12, [&](std::size_t c, std::string& o) {
    if (number_cells)
      append_int(o, std::int64_t(c));
    else
      o += lead;
    for (std::size_t j = 0; j < kk; ++j) {
      o += ' ';
      append_int(o, std::int64_t(cells[c * kk + j]) + base);
    }
    o += '\n';
  });
}

bool data_array_from(const std::string& name, ScalarType type, int components,
                     const std::vector<double>& v, DataArray& a) {
  double lo = 0, hi = 0;
  switch (type) {
    case ScalarType::Bool:
    case ScalarType::U8:
      lo = 0, hi = 255;
      break;
    case ScalarType::U16:
      lo = 0, hi = 65535;
      break;
    case ScalarType::I32:
      lo = -2147483648.0, hi = 2147483647.0;
      break;
    case ScalarType::I64:  // (doubles from 2^63 up do not fit)
      lo = -9223372036854775808.0, hi = 9223372036854774784.0;
      break;
    default:
      break;
  }
  const bool integer = type != ScalarType::F32 && type != ScalarType::F64;
  if (integer)
    for (double x : v)
      if (!(x >= lo && x <= hi)) return false;  // (NaN included)
  a.name = name;
  a.type = type;
  a.components = components;
  a.bytes.resize(v.size() * scalar_size(type));
  unsigned char* p = a.bytes.data();
  visit_scalar(type, [&](auto zero) {
    using T = decltype(zero);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const T x = T(v[i]);  // (a float out of range: inf, as a cast of a double does)
      std::memcpy(p + i * sizeof x, &x, sizeof x);
    }
  });
  return true;
}

void append_value(std::string& o, const DataArray& d, std::size_t i) {
  const unsigned char* p = d.bytes.data() + i * scalar_size(d.type);
  visit_scalar(d.type, [&](auto x) {
    std::memcpy(&x, p, sizeof x);
    if constexpr (std::is_floating_point_v<decltype(x)>)
      append_double(o, double(x));
    else
      append_int(o, std::int64_t(x));
  });
}

void append_int(std::string& out, std::int64_t v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void append_double(std::string& out, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace gpugeom::io::detail
