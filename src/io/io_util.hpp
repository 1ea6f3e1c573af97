// Shared helpers of the readers and writers: whole-file reads, atomic writes, a line cursor
// that knows where it is for error messages, and number parsing.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "gpugeom/common.hpp"

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
  [[noreturn]] void fail(const std::string& what) const { parse_fail(name_, line_, what); }

 private:
  std::string_view t_;
  std::string name_;
  std::size_t pos_ = 0;
  std::int64_t line_ = 0;
};

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

}  // namespace gpugeom::io::detail
