// Shared helpers of the readers and writers: whole-file reads, atomic writes, a line cursor
// that knows where it is for error messages, and number parsing.
#pragma once
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "base/type_visit.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::io::detail {

std::string read_file(const std::string& path);
// The file beside path with the extension ext instead of its own (a .ele's .node).
std::string sibling(const std::string& path, const std::string& ext);

// A base of the classes below, which own an open file: they are neither copied nor moved.
struct OwnsFile {
  OwnsFile() = default;
  OwnsFile(const OwnsFile&) = delete;
  OwnsFile& operator=(const OwnsFile&) = delete;
};

// A read-only view of a whole file without a copy: mapped where the system allows (its pages
// come in as the parsers touch them, on the parsers' threads), else read into memory. Opening
// errors are read_file's.
class FileView : OwnsFile {
 public:
  explicit FileView(const std::string& path);
  ~FileView();
  std::string_view view() const { return map_ ? std::string_view(map_, size_) : copy_; }

 private:
  const char* map_ = nullptr;
  std::size_t size_ = 0;
  std::string copy_;
};
// parse(text, ext, path) over the file at path, mapped, where ext is one of the known
// extensions; for any other, parse("", ext, path), which reports the unknown format before the
// file is touched.
template <std::size_t N, class Parse>
auto parse_file(const std::string& path, const std::string& ext, const char* const (&known)[N],
                Parse parse) {
  if (std::find(std::begin(known), std::end(known), ext) == std::end(known))
    return parse(std::string_view(), ext, path);
  const FileView f(path);  // (mapped: parsed where the page cache holds it, no copy)
  return parse(f.view(), ext, path);
}
// A file written piece by piece to path.tmp-XXXX beside the target and renamed over path by
// commit(); destroyed without commit() (an error on the way), the temporary is removed, so a
// failure never leaves a half-written file. Errors are Error(Io) naming the target.
class AtomicFile : OwnsFile {
 public:
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  void write(const void* data, std::size_t bytes);
  void write(std::string_view s) { write(s.data(), s.size()); }
  void commit();

 private:
  [[noreturn]] void fail(int err);
  std::string path_, tmp_;
  std::FILE* f_ = nullptr;
};
// Text in pieces, kept in order: what the text writers produce, written to the file piece by
// piece, so a large file is never joined into one string (a serial zero-fill and copy of its
// whole size before the first byte is written). Short appends go onto the last piece while it
// is short; long pieces (a section formatted on all threads) are moved in whole.
class Text {
 public:
  Text() = default;
  Text(std::string s) { *this += std::move(s); }  // NOLINT: a string is one piece of text
  Text(const char* s) : Text(std::string(s)) {}   // NOLINT
  Text& operator+=(std::string s) {
    constexpr std::size_t kShort = std::size_t(1) << 16;
    if (s.empty()) return *this;
    if (!p_.empty() && p_.back().size() < kShort && s.size() < kShort)
      p_.back() += s;
    else
      p_.push_back(std::move(s));
    return *this;
  }
  Text& operator+=(const char* s) { return *this += std::string(s); }
  Text& operator+=(char c) { return *this += std::string(1, c); }
  Text& operator+=(Text t) {
    for (std::string& s : t.p_) *this += std::move(s);
    return *this;
  }
  std::size_t size() const {
    std::size_t n = 0;
    for (const std::string& s : p_) n += s.size();
    return n;
  }
  std::string str() const {  // joined, for callers that need one string
    std::string o;
    o.reserve(size());
    for (const std::string& s : p_) o += s;
    return o;
  }
  const std::vector<std::string>& pieces() const { return p_; }

 private:
  std::vector<std::string> p_;
};

// Writes bytes to path through an AtomicFile.
void write_file_atomic(const std::string& path, const std::string& bytes);
void write_file_atomic(const std::string& path, const Text& text);

[[noreturn]] void parse_fail(const std::string& name, std::int64_t line, const std::string& what);

// Iterates over lines (any of \n, \r\n), skipping blank lines and '#' comments when asked.
class Lines {
 public:
  Lines(std::string_view text, std::string name) : t_(text), name_(std::move(name)) {}
  // A part of a file that starts after `lines_before` lines (line numbers count on from there).
  Lines(std::string_view text, std::string name, std::int64_t lines_before)
      : t_(text), name_(std::move(name)), line_(lines_before) {}
  bool next(std::string_view& line, bool skip_comments = true);
  std::int64_t line_no() const { return line_; }
  const std::string& name() const { return name_; }
  std::size_t offset() const { return pos_; }  // byte offset after the current line
  // Continues after a section another reader took: at byte pos, after `lines` lines.
  void skip_to(std::size_t pos, std::int64_t lines) { pos_ = pos, line_ = lines; }
  [[noreturn]] void fail(const std::string& what) const { parse_fail(name_, line_, what); }

 private:
  std::string_view t_;
  std::string name_;
  std::size_t pos_ = 0;
  std::int64_t line_ = 0;
};

// Counts the line ends of text and the lines Lines::next returns (not blank, not a comment).
void count_lines(std::string_view text, std::int64_t& ends, std::int64_t& data);
int host_threads();  // the threads a parallel reader may use

// A counted section of a text format (the points of a .node file, the cells of a .ele file,
// the vertices and faces of an .off file), read in parallel: the rest of l's text is cut at
// line ends into parts, each part's line ends and records counted first (so it knows its first
// line number and first record), the part holding the count-th record cut after it, and the
// parts parsed on their own threads. record(part, line, index, out) reads record `index`
// (failing through `part`, which numbers lines as l would) into out[0 .. per). l continues after
// the section. Errors are those of a serial loop, the first in file order; too few records fail
// with short(i) for the i found, on the line a serial loop would name. count < 0: every record
// to the end of the text (a table without a count).
// Where text is cut into parts for the parallel readers: one per host thread, at least 1 MiB
// each, each starting at a line start; start[k] .. start[k + 1] is part k (start.back() is the
// end).
inline std::vector<std::size_t> line_parts(std::string_view rest) {
  constexpr std::size_t kMinPart = std::size_t(1) << 20;
  const std::size_t nparts = std::max<std::size_t>(
      1, std::min<std::size_t>(std::size_t(host_threads()), rest.size() / kMinPart));
  std::vector<std::size_t> start(nparts + 1, rest.size());
  start[0] = 0;
  for (std::size_t k = 1; k < nparts; ++k) {
    const std::size_t nl = rest.find('\n', k * rest.size() / nparts);
    start[k] = nl == std::string_view::npos ? rest.size() : std::max(start[k - 1], nl + 1);
  }
  return start;
}

template <class V, class Record, class Short>
void read_records(Lines& l, std::string_view text, std::int64_t count, int per, V& out,
                  Record record, Short short_message) {
  using T = typename V::value_type;
  const std::size_t base = std::min(l.offset(), text.size());
  const std::string_view rest = text.substr(base);
  const std::vector<std::size_t> start = line_parts(rest);
  const std::size_t nparts = start.size() - 1;
  std::vector<std::int64_t> lines(nparts + 1, 0), recs(nparts + 1, 0);
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t k = 0; k < std::int64_t(nparts); ++k) {
    const std::size_t i = std::size_t(k);
    count_lines(rest.substr(start[i], start[i + 1] - start[i]), lines[i + 1], recs[i + 1]);
  }
  lines[0] = l.line_no();
  for (std::size_t k = 0; k < nparts; ++k) lines[k + 1] += lines[k], recs[k + 1] += recs[k];
  if (count < 0) count = recs[nparts];
  // The section's end: after the count-th record, in the part that holds it.
  std::size_t used = nparts;
  std::size_t end = rest.size();
  std::int64_t end_line = lines[nparts] + (!rest.empty() && rest.back() != '\n' ? 1 : 0);
  for (std::size_t k = 0; k < nparts; ++k)
    if (recs[k + 1] >= count) {
      used = k + 1;
      Lines scan(rest.substr(start[k], start[k + 1] - start[k]), l.name(), lines[k]);
      std::string_view line;
      for (std::int64_t r = recs[k]; r < count; ++r) scan.next(line);
      end = start[k] + scan.offset();
      end_line = scan.line_no();
      if (count == recs[k]) end = start[k], end_line = lines[k];
      break;
    }
  const std::int64_t found = std::min(count, recs[used]);
  const std::size_t head = out.size();
  out.resize(head + std::size_t(per) * std::size_t(found));
  std::vector<std::string> error(used);
  std::vector<ErrorCode> code(used, ErrorCode::Internal);
  std::vector<char> any(used, 0);
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t k = 0; k < std::int64_t(used); ++k) {
    const std::size_t i = std::size_t(k);
    const std::size_t to = std::min(start[i + 1], end);
    if (to <= start[i]) continue;
    try {
      Lines part(rest.substr(start[i], to - start[i]), l.name(), lines[i]);
      std::string_view line;
      T* o = out.data() + head + std::size_t(per) * std::size_t(recs[i]);
      for (std::int64_t r = recs[i]; r < found && part.next(line); ++r, o += per)
        record(part, line, r, o);
    } catch (const Error& e) {  // (an exception may not leave a parallel region)
      any[i] = 1;
      code[i] = e.code();
      error[i] = e.what();
    }
  }
  for (std::size_t k = 0; k < used; ++k)
    if (any[k]) throw Error(code[k], error[k]);
  l.skip_to(base + end, end_line);
  if (found < count) l.fail(short_message(found));
}

// The tokens of a line: the first kInline stored in place, so the parsers' hot loops (one
// split per line, on every host thread) do not allocate; longer lines spill to a vector.
class Tokens {
 public:
  std::size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  std::string_view operator[](std::size_t i) const { return data()[i]; }
  const std::string_view* begin() const { return data(); }
  const std::string_view* end() const { return data() + n_; }
  void push(std::string_view s) {
    if (n_ < kInline) {
      in_[n_++] = s;
      return;
    }
    if (n_ == kInline) more_.assign(in_, in_ + kInline);
    more_.push_back(s);
    ++n_;
  }
  void drop_front();

 private:
  static constexpr std::size_t kInline = 12;
  const std::string_view* data() const { return n_ <= kInline ? in_ : more_.data(); }
  std::string_view in_[kInline];
  std::vector<std::string_view> more_;  // all tokens, once there are more than kInline
  std::size_t n_ = 0;
};

// A token separator as the text readers see it: spaces, tabs, line ends and, when commas is
// true, commas (split, next_token and Scan share it, so both paths cut lines alike).
inline bool is_separator(char c, bool commas) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || (commas && c == ',');
}

// The next token of s from pos on (separators: spaces, tabs, line ends and, when commas is
// true, commas); false when none is left. pos moves past it.
inline bool next_token(std::string_view s, std::size_t& pos, std::string_view& tok,
                       bool commas = false) {
  auto sep = [&](char c) { return is_separator(c, commas); };
  std::size_t i = pos;
  while (i < s.size() && sep(s[i])) ++i;
  std::size_t j = i;
  while (j < s.size() && !sep(s[j])) ++j;
  pos = j;
  if (j == i) return false;
  tok = s.substr(i, j - i);
  return true;
}

// The parsers' fast path: numbers read straight from a line, token by token, with no token
// list in between. Each call takes the next token only when it is a whole number as
// to_double / to_int64 read it; otherwise it returns false and the caller takes its split()
// path, which produces the exact error message (so the messages do not depend on the path).
class Scan {
 public:
  explicit Scan(std::string_view s, bool commas = false) : s_(s), commas_(commas) {}
  template <class T>
  bool next(T& v) {
    skip();
    const char* p = s_.data() + pos_;
    const char* e = s_.data() + s_.size();
    if (p == e) return false;
    if (*p == '+') ++p;
    const auto r = std::from_chars(p, e, v);
    if (r.ec != std::errc() || (r.ptr != e && !sep(*r.ptr))) return false;
    pos_ = std::size_t(r.ptr - s_.data());
    return true;
  }
  bool done() {  // nothing but separators left
    skip();
    return pos_ == s_.size();
  }

 private:
  bool sep(char c) const { return is_separator(c, commas_); }
  void skip() {
    while (pos_ < s_.size() && sep(s_[pos_])) ++pos_;
  }
  std::string_view s_;
  bool commas_;
  std::size_t pos_ = 0;
};

// True when every v[0 .. n) is in [lo, hi).
inline bool in_range(const std::int64_t* v, int n, std::int64_t lo, std::int64_t hi) {
  for (int i = 0; i < n; ++i)
    if (v[i] < lo || v[i] >= hi) return false;
  return true;
}

// Splits on spaces, tabs and (when commas is true) commas.
Tokens split(std::string_view line, bool commas = false);
bool to_double(std::string_view s, double& v);
bool to_int64(std::string_view s, std::int64_t& v);
double need_double(const Lines& l, std::string_view s, const char* what);
std::int64_t need_int(const Lines& l, std::string_view s, const char* what);

// npy container: descr like "<f8", shape, C order only.
struct NpyArray {
  std::string descr;
  std::vector<std::int64_t> shape;
  std::string_view payload;
};
NpyArray parse_npy(std::string_view bytes, const std::string& name);
std::string format_npy(const std::string& descr, const std::vector<std::int64_t>& shape,
                       const void* data, std::size_t bytes);
// Element i of an npy payload as a double; supports the descr codes listed in io.hpp.
double npy_value(const NpyArray& a, std::int64_t i, const std::string& name);
// Element i of an integer or bool array, exactly (uint64 above 2^63-1 is a parse error).
std::int64_t npy_integer(const NpyArray& a, std::int64_t i, const std::string& name);
std::size_t npy_item_size(const std::string& descr, const std::string& name);

// PLY: vertices and one list element of faces or tetrahedra.
struct PlyData {
  int dim = 3;
  HostVector<double> coords;
  int cell_size = 0;
  HostVector<std::int32_t> cells;
};
PlyData parse_ply(std::string_view bytes, const std::string& name);
Text format_ply(const double* coords, int dim, std::size_t nv, const std::int32_t* cells,
                int cell_size, std::size_t nc, bool binary);

// Gmsh MSH 2.2 ASCII (msh.cpp): nodes and triangles or tetrahedra, region tags from a cell
// array "attribute" of integers.
Text format_msh(const Mesh& m);

void append_double(std::string& out, double v);  // shortest round-trip text
void append_int(std::string& out, std::int64_t v);
// A data array of `type` from values read as doubles (the readers' common form); false, with
// nothing converted, when a value does not fit the type (the file's values are then not what
// its type says: the reader's Parse error).
bool data_array_from(const std::string& name, ScalarType type, int components,
                     const std::vector<double>& values, DataArray& out);
// Value i of a data array as text (integers exactly, floats as their shortest round trip).
void append_value(std::string& out, const DataArray& d, std::size_t i);
// Lines of 3 coordinates (2D points padded with z = 0), each after `prefix` (OFF, OBJ "v ").
Text format_vertex_lines(const double* coords, int dim, std::size_t n, const char* prefix);
// Lines of cells: `lead` (a count, "f", or the cell's number when number_cells), then the
// indices plus `base`.
Text format_cell_lines(const std::int32_t* cells, int k, std::size_t n, const char* lead,
                       bool number_cells, int base);

// Text of n lines, line(i, out) appending line i (with its '\n'), formatted on all host threads
// in ranges of lines, each into its own buffer, kept in order as the pieces of one Text: the
// same bytes as one thread writes. `bytes_per_line` sizes the buffers.
template <class F>
Text format_lines(std::size_t n, std::size_t bytes_per_line, F line) {
  const std::size_t nparts =
      std::max<std::size_t>(1, std::min<std::size_t>(std::size_t(host_threads()), n / 65536));
  std::vector<std::string> part(nparts);
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t k = 0; k < std::int64_t(nparts); ++k) {
    const std::size_t lo = std::size_t(k) * n / nparts, hi = (std::size_t(k) + 1) * n / nparts;
    std::string& o = part[std::size_t(k)];
    o.reserve((hi - lo) * bytes_per_line);
    for (std::size_t i = lo; i < hi; ++i) line(i, o);
  }
  Text out;
  for (std::string& s : part) out += std::move(s);
  return out;
}

// A binary element type as the mesh formats declare them (VTU's Int32, VTK's int, ...): its size
// and kind ('i' signed, 'u' unsigned, 'f' float).
struct NumType {
  int bytes = 0;
  char kind = 0;
};

// f(T{}) with T the C++ type of a binary element type (the type decided once, not per element);
// double for what is none of them.
template <class F>
void visit_num(const NumType& e, F&& f) {
  using Types = std::tuple<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t, std::int32_t,
                           std::uint32_t, std::int64_t, std::uint64_t, float, double>;
  const int width = e.bytes == 1 ? 0 : e.bytes == 2 ? 1 : e.bytes == 4 ? 2 : e.bytes == 8 ? 3 : -1;
  std::size_t i = 9;  // double
  if ((e.kind == 'i' || e.kind == 'u') && width >= 0)
    i = std::size_t(2 * width + (e.kind == 'u'));
  else if (e.kind == 'f' && e.bytes == 4)
    i = 8;
  gpugeom::detail::visit_type<Types>(i, std::forward<F>(f));
}

// Element i of type T from raw bytes, big-endian files swapped.
template <class T>
T num_at(const unsigned char* p, std::size_t i, bool big) {
  constexpr std::size_t w = sizeof(T);
  unsigned char b[w];
  const unsigned char* q = p + i * w;
  for (std::size_t k = 0; k < w; ++k) b[k] = big ? q[w - 1 - k] : q[k];
  T v;
  std::memcpy(&v, b, w);
  return v;
}

}  // namespace gpugeom::io::detail
