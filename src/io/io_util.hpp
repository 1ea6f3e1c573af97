// Shared helpers of the readers and writers: whole-file reads, atomic writes, a line cursor
// that knows where it is for error messages, and number parsing.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::io::detail {

std::string read_file(const std::string& path);

// A read-only view of a whole file without a copy: mapped where the system allows (its pages
// come in as the parsers touch them, on the parsers' threads), else read into memory. Opening
// errors are read_file's.
class FileView {
 public:
  explicit FileView(const std::string& path);
  ~FileView();
  FileView(const FileView&) = delete;
  FileView& operator=(const FileView&) = delete;
  std::string_view view() const { return map_ ? std::string_view(map_, size_) : copy_; }

 private:
  const char* map_ = nullptr;
  std::size_t size_ = 0;
  std::string copy_;
};
// A file written piece by piece to path.tmp-XXXX beside the target and renamed over path by
// commit(); destroyed without commit() (an error on the way), the temporary is removed, so a
// failure never leaves a half-written file. Errors are Error(Io) naming the target.
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  void write(const void* data, std::size_t bytes);
  void write(std::string_view s) { write(s.data(), s.size()); }
  void commit();

 private:
  [[noreturn]] void fail(int err);
  std::string path_, tmp_;
  std::FILE* f_ = nullptr;
};
// Writes bytes to path through an AtomicFile.
void write_file_atomic(const std::string& path, const std::string& bytes);

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

template <class T, class Record, class Short>
void read_records(Lines& l, std::string_view text, std::int64_t count, int per, std::vector<T>& out,
                  Record record, Short short_message) {
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

// Splits on spaces, tabs and (when commas is true) commas.
std::vector<std::string_view> split(std::string_view line, bool commas = false);
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
NpyArray parse_npy(const std::string& bytes, const std::string& name);
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
  std::vector<double> coords;
  int cell_size = 0;
  std::vector<std::int32_t> cells;
};
PlyData parse_ply(const std::string& bytes, const std::string& name);
std::string format_ply(const double* coords, int dim, std::size_t nv, const std::int32_t* cells,
                       int cell_size, std::size_t nc, bool binary);

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
std::string format_vertex_lines(const double* coords, int dim, std::size_t n, const char* prefix);
// Lines of cells: `lead` (a count, "f", or the cell's number when number_cells), then the
// indices plus `base`.
std::string format_cell_lines(const std::int32_t* cells, int k, std::size_t n, const char* lead,
                              bool number_cells, int base);

// Text of n lines, line(i, out) appending line i (with its '\n'), formatted on all host threads
// in ranges of lines, each into its own buffer, then joined in order: the same bytes as one
// thread writes. `bytes_per_line` sizes the buffers.
template <class F>
std::string format_lines(std::size_t n, std::size_t bytes_per_line, F line) {
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
  std::vector<std::size_t> at(nparts + 1, 0);
  for (std::size_t k = 0; k < nparts; ++k) at[k + 1] = at[k] + part[k].size();
  std::string out(at[nparts], '\0');
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t k = 0; k < std::int64_t(nparts); ++k)
    std::memcpy(&out[at[std::size_t(k)]], part[std::size_t(k)].data(), part[std::size_t(k)].size());
  return out;
}

// A binary element type as the mesh formats declare them (VTU's Int32, VTK's int, ...): its size
// and kind ('i' signed, 'u' unsigned, 'f' float).
struct NumType {
  int bytes = 0;
  char kind = 0;
};

// f(T{}) with T the C++ type of a binary element type (the type decided once, not per element).
template <class F>
void visit_num(const NumType& e, F&& f) {
  switch (e.kind * 16 + e.bytes) {
    case 'i' * 16 + 1:
      return f(std::int8_t{});
    case 'u' * 16 + 1:
      return f(std::uint8_t{});
    case 'i' * 16 + 2:
      return f(std::int16_t{});
    case 'u' * 16 + 2:
      return f(std::uint16_t{});
    case 'i' * 16 + 4:
      return f(std::int32_t{});
    case 'u' * 16 + 4:
      return f(std::uint32_t{});
    case 'i' * 16 + 8:
      return f(std::int64_t{});
    case 'u' * 16 + 8:
      return f(std::uint64_t{});
    case 'f' * 16 + 4:
      return f(float{});
    default:
      return f(double{});
  }
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
