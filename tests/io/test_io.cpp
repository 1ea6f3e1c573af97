// Round trips for every format, and one test per kind of malformed input.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <charconv>
#include <cmath>
#include <cstring>
#include <iterator>
#include <random>
#include <omp.h>
#include <unistd.h>

#include "gpugeom/generate.hpp"
#include "gpugeom/io.hpp"

using namespace gpugeom;
namespace fs = std::filesystem;

namespace {

// One folder per test process, removed when the process ends (a run left one behind before).
std::string tmpdir() {
  static std::string d = [] {
    auto p = fs::temp_directory_path() / ("gg_io_" + std::to_string(::getpid()));
    fs::create_directories(p);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(fs::temp_directory_path() / ("gg_io_" + std::to_string(::getpid())), ec);
    });
    return p.string();
  }();
  return d;
}
std::string path(const std::string& name) {
  return tmpdir() + "/" + name;
}
void write_text(const std::string& p, const std::string& s) {
  std::ofstream(p, std::ios::binary) << s;
}
bool no_temp_files() {
  for (auto& e : fs::directory_iterator(tmpdir()))
    if (e.path().string().find(".tmp-") != std::string::npos) return false;
  return true;
}

io::PointSet sample(int dim, int n) {
  io::PointSet p;
  p.dim = dim;
  if (dim == 2) {
    for (auto& q : generate2d("gaussian", n, 3)) p.coords.insert(p.coords.end(), {q.x, q.y});
  } else {
    for (auto& q : generate3d("gaussian", n, 3)) p.coords.insert(p.coords.end(), {q.x, q.y, q.z});
  }
  p.coords[0] = 1e-300;  // extremes survive text formats exactly
  p.coords[1] = -1.2345678901234567e300;
  return p;
}

std::string expect_parse_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ErrorCode::Parse)) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no parse error";
  return "";
}

}  // namespace

TEST(Io, PointRoundTrips) {
  for (int dim : {2, 3})
    for (std::string ext : {".xyz", ".txt", ".csv", ".ply", ".npy", ".node", ".off", ".obj"}) {
      if ((ext == ".off" || ext == ".obj") && dim == 2) continue;  // 3D formats
      auto p = sample(dim, 1000);
      for (bool binary : {true, false}) {
        if (!binary && ext != ".ply") continue;
        io::WriteOptions o;
        o.binary = binary;
        const std::string f = path("p" + std::to_string(dim) + ext);
        io::write_points(f, p, o);
        auto q = io::read_points(f);
        EXPECT_EQ(q.dim, dim) << ext;
        EXPECT_EQ(q.coords, p.coords) << ext << " binary=" << binary;
      }
    }
  EXPECT_TRUE(no_temp_files());
}

// Text tables are read in parallel parts: the values and the errors (message and line number)
// must be those of a line-by-line read, whatever the number of threads and wherever the parts
// are cut (blank lines, comments, CRLF and comma lines on the way).
TEST(Io, TextTablesInPartsAsOneReadWould) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  const std::size_t n = 250000;  // about 13 MB: several 1 MiB parts
  std::vector<double> want;
  std::string text = "x y z\n";
  std::vector<std::int64_t> line_of(n);  // the file line of each point
  std::int64_t line = 1;
  for (std::size_t i = 0; i < n; ++i) {
    if (i % 9973 == 0) text += "# a comment\n", ++line;
    if (i % 7919 == 0) text += "   \n", ++line;
    double v[3] = {u(rng), u(rng), std::ldexp(u(rng), int(i % 60) - 30)};
    char buf[96];
    std::snprintf(buf, sizeof buf, i % 5 == 0 ? "%.17g,%.17g,%.17g\r\n" : "%.17g %.17g %.17g\n",
                  v[0], v[1], v[2]);
    text += buf;
    line_of[i] = ++line;
    want.insert(want.end(), v, v + 3);
  }
  const std::string f = path("big.xyz");
  write_text(f, text);
  const int threads0 = omp_get_max_threads();
  for (int threads : {1, 2, 3, 7}) {
    omp_set_num_threads(threads);
    const auto p = io::read_points(f);
    EXPECT_EQ(p.dim, 3);
    EXPECT_EQ(p.coords, want) << threads << " threads";
    // an error late in the file, one in the middle: file:line: message, as read line by line
    for (std::size_t bad : {n - 3, n / 2 + 11, std::size_t(5)}) {
      std::string t = text;
      const std::string token = "1.5 2.5 oops\n";
      std::size_t at = 0;  // the start of point `bad`'s line
      for (std::int64_t l = 1; l < line_of[bad]; ++l) at = t.find('\n', at) + 1;
      t.replace(at, t.find('\n', at) + 1 - at, token);
      write_text(path("bad.xyz"), t);
      try {
        io::read_points(path("bad.xyz"));
        ADD_FAILURE() << "accepted a bad line";
      } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::Parse);
        EXPECT_EQ(std::string(e.what()), path("bad.xyz") + ":" + std::to_string(line_of[bad]) +
                                             ": expected a number for a coordinate, found 'oops'")
            << threads << " threads";
      }
    }
  }
  omp_set_num_threads(threads0);
  // written in parallel parts: the same bytes as point by point
  io::PointSet ps;
  ps.dim = 3;
  ps.coords.assign(want.begin(), want.end());
  io::write_points(path("out.xyz"), ps);
  std::string serial;
  for (std::size_t i = 0; i < n; ++i) {
    char buf[96];
    for (int d = 0; d < 3; ++d) {
      auto r = std::to_chars(buf, buf + sizeof buf, want[3 * i + d]);
      serial.append(d ? " " : "");
      serial.append(buf, r.ptr);
    }
    serial += '\n';
  }
  std::ifstream in(path("out.xyz"), std::ios::binary);
  const std::string got((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(got == serial);
  EXPECT_TRUE(no_temp_files());
}

// OBJ in parallel parts: vertices and faces (relative indices counting back from the vertices
// defined so far, across parts), and the first error in file order with its line, on any
// number of threads.
TEST(Io, ObjInPartsAsOneReadWould) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-10, 10);
  std::string text = "# an OBJ file\nmtllib x.mtl\n";
  std::vector<double> coords;
  std::vector<std::int32_t> cells;
  std::vector<std::int64_t> face_line;
  std::int64_t line = 2, nv = 0;
  for (int i = 0; i < 200000; ++i) {  // about 8 MB: several 1 MiB parts
    char buf[96];
    double v[3] = {u(rng), u(rng), u(rng)};
    std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", v[0], v[1], v[2]);
    text += buf, ++line, ++nv;
    coords.insert(coords.end(), v, v + 3);
    if (i % 11 == 0) text += "vn 0 0 1\n", ++line;
    if (nv >= 3 && i % 2 == 0) {
      if (i % 4 == 0) {  // absolute, with texture / normal parts
        std::snprintf(buf, sizeof buf, "f %lld/1 %lld//2 %lld\n", (long long)nv - 2,
                      (long long)nv - 1, (long long)nv);
      } else {  // relative
        std::snprintf(buf, sizeof buf, "f -3 -2 -1\n");
      }
      text += buf, ++line;
      face_line.push_back(line);
      cells.insert(cells.end(), {std::int32_t(nv - 3), std::int32_t(nv - 2), std::int32_t(nv - 1)});
    }
  }
  const std::string f = path("big.obj");
  write_text(f, text);
  const int threads0 = omp_get_max_threads();
  for (int threads : {1, 2, 3, 7}) {
    omp_set_num_threads(threads);
    const auto m = io::read_mesh(f);
    EXPECT_EQ(m.coords, coords) << threads;
    EXPECT_EQ(m.cells, cells) << threads;
    // a face that refers past the vertices defined before it, late and early in the file
    for (std::size_t bad : {face_line.size() - 5, face_line.size() / 2, std::size_t(3)}) {
      std::string t = text;
      std::size_t at = 0;
      for (std::int64_t l = 1; l < face_line[bad]; ++l) at = t.find('\n', at) + 1;
      t.replace(at, t.find('\n', at) + 1 - at, "f 1 2 99999999\n");
      write_text(path("bad.obj"), t);
      try {
        io::read_mesh(path("bad.obj"));
        ADD_FAILURE() << "accepted a bad face";
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  path("bad.obj") + ":" + std::to_string(face_line[bad]) +
                      ": face refers to vertex 99999999 which is not defined yet")
            << threads << " threads";
      }
    }
  }
  omp_set_num_threads(threads0);
}

// Counted sections (.node points, .ele cells, .off vertices and faces) are read in parallel
// parts too: values, the section ends, and errors (message, line) as a serial read gives them.
TEST(Io, CountedSectionsInPartsAsOneReadWould) {
  const std::int64_t n = 120000, nc = 100000;  // several 1 MiB parts in each file
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-10, 10);
  std::vector<double> xy(std::size_t(2 * n));
  for (auto& v : xy) v = u(rng);
  std::vector<std::int32_t> cells(std::size_t(3 * nc));
  for (auto& c : cells) c = std::int32_t(rng() % std::uint32_t(n));
  // .node (1-based) with comments and blank lines; .ele beside it
  std::string node = "# points\n" + std::to_string(n) + " 2 0 0\n";
  std::vector<std::int64_t> node_line(static_cast<std::size_t>(n));
  std::int64_t line = 2;
  for (std::int64_t i = 0; i < n; ++i) {
    if (i % 5003 == 0) node += "\n# more\n", line += 2;
    char buf[96];
    std::snprintf(buf, sizeof buf, "%lld %.17g %.17g\n", (long long)(i + 1), xy[2 * i],
                  xy[2 * i + 1]);
    node += buf;
    node_line[std::size_t(i)] = ++line;
  }
  std::string ele = std::to_string(nc) + " 3 0\n";
  std::vector<std::int64_t> ele_line(static_cast<std::size_t>(nc));
  line = 1;
  for (std::int64_t c = 0; c < nc; ++c) {
    if (c % 7001 == 0) ele += "   \n", ++line;
    ele += std::to_string(c + 1) + " " + std::to_string(cells[3 * c] + 1) + " " +
           std::to_string(cells[3 * c + 1] + 1) + " " + std::to_string(cells[3 * c + 2] + 1) + "\n";
    ele_line[std::size_t(c)] = ++line;
  }
  // .off with the same points (z = 0.5) and faces
  std::string off = "OFF\n" + std::to_string(n) + " " + std::to_string(nc) + " 0\n";
  for (std::int64_t i = 0; i < n; ++i) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.17g %.17g 0.5\n", xy[2 * i], xy[2 * i + 1]);
    off += buf;
  }
  for (std::int64_t c = 0; c < nc; ++c)
    off += "3 " + std::to_string(cells[3 * c]) + " " + std::to_string(cells[3 * c + 1]) + " " +
           std::to_string(cells[3 * c + 2]) + "\n";
  auto replace_line = [](std::string t, std::int64_t at_line, const std::string& with) {
    std::size_t at = 0;
    for (std::int64_t l = 1; l < at_line; ++l) at = t.find('\n', at) + 1;
    t.replace(at, t.find('\n', at) + 1 - at, with);
    return t;
  };
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const int threads0 = omp_get_max_threads();
  for (int threads : {1, 2, 3, 7}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    omp_set_num_threads(threads);
    write_text(path("s.node"), node);
    write_text(path("s.ele"), ele);
    write_text(path("s.off"), off);
    const auto m = io::read_mesh(path("s.ele"));
    EXPECT_EQ(m.coords, xy);
    EXPECT_EQ(m.cells, cells);
    const auto o = io::read_mesh(path("s.off"));
    EXPECT_EQ(o.cells, cells);
    ASSERT_EQ(o.coords.size(), std::size_t(3 * n));
    EXPECT_EQ(o.coords[3 * (n - 1) + 1], xy[2 * (n - 1) + 1]);
    // errors deep in a section, with the serial line numbers
    write_text(path("b.node"), replace_line(node, node_line[std::size_t(n - 7)], "9 1.0 x\n"));
    EXPECT_EQ(message([&] { io::read_points(path("b.node")); }),
              path("b.node") + ":" + std::to_string(node_line[std::size_t(n - 7)]) +
                  ": expected a number for a coordinate, found 'x'");
    write_text(path("b.ele"), replace_line(ele, ele_line[std::size_t(nc / 2)], "5 1 2\n"));
    write_text(path("b.node"), node);
    std::string be = path("b.ele");
    EXPECT_EQ(message([&] { io::read_mesh(be); }),
              be + ":" + std::to_string(ele_line[std::size_t(nc / 2)]) +
                  ": expected '<index>' and 3 vertex indices");
    // too few records: the count of those found, on the last line
    std::string cut = ele.substr(0, ele.rfind('\n', ele.size() - 2) + 1);  // drop the last cell
    write_text(be, cut);
    const std::int64_t last_line = std::count(cut.begin(), cut.end(), '\n');
    EXPECT_EQ(message([&] { io::read_mesh(be); }),
              be + ":" + std::to_string(last_line) + ": file ends after " + std::to_string(nc - 1) +
                  " of " + std::to_string(nc) + " cells");
  }
  omp_set_num_threads(threads0);
}

// Little-endian binary PLY as other tools write it: properties in any order and of mixed types
// (the fast path picks x, y, z out of each record), face lists of unsigned ints; a bad index and
// mixed list lengths keep their messages.
TEST(Io, PlyLittleEndianMixedLayouts) {
  const std::size_t n = 100000;  // (parallel above 65536 records)
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                  "\nproperty float z\nproperty double x\nproperty uchar red\nproperty int y\n"
                  "element face " +
                  std::to_string(n - 2) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  const std::size_t body = s.size();
  auto raw = [&](auto v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); };
  std::vector<double> want;
  for (std::size_t i = 0; i < n; ++i) {
    const float z = float(i) * 0.5f;
    const double x = double(i) / 3.0;
    const std::int32_t y = -std::int32_t(i);
    raw(z), raw(x), raw(std::uint8_t(i)), raw(y);
    want.insert(want.end(), {x, double(y), double(z)});
  }
  std::vector<std::int32_t> cells;
  for (std::uint32_t i = 0; i + 2 < n; ++i) {
    raw(std::uint8_t(3)), raw(i), raw(i + 1), raw(i + 2);
    cells.insert(cells.end(), {std::int32_t(i), std::int32_t(i + 1), std::int32_t(i + 2)});
  }
  const auto m = io::parse_mesh(s, ".ply", "le.ply");
  EXPECT_EQ(m.coords, want);
  EXPECT_EQ(m.cells, cells);
  const std::size_t faces = body + n * 17;  // the first face record
  std::string bad = s;
  const std::uint32_t huge = 0x80000000u;
  std::memcpy(&bad[faces + 5 * 13 + 1 + 4], &huge, 4);  // face 5, second index
  try {
    io::parse_mesh(bad, ".ply", "le.ply");
    ADD_FAILURE() << "accepted a bad index";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("face 5 has an invalid vertex index"), std::string::npos)
        << e.what();
  }
  std::string four = s;
  four[faces + 7 * 13] = 4;  // face 7 claims 4 indices
  try {
    io::parse_mesh(four, ".ply", "le.ply");
    ADD_FAILURE() << "accepted a quad";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("face 7 has 4 indices"), std::string::npos) << e.what();
  }
}

// ASCII PLY, one item per line (read in parallel parts) and the same items laid out otherwise
// (two vertices to a line: the token reader), give the same mesh; errors keep the serial
// reader's message and line.
TEST(Io, PlyAsciiInPartsAsTheTokenReader) {
  const std::size_t n = 120000;  // several 1 MiB parts
  std::string head = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(n) +
                     "\nproperty float z\nproperty double x\nproperty uchar red\nproperty int y\n"
                     "element face " +
                     std::to_string(n - 2) +
                     "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string lines = head, paired = head;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-100, 100);
  std::vector<double> want;
  for (std::size_t i = 0; i < n; ++i) {
    char buf[128];
    const double x = u(rng), z = double(float(u(rng)));
    const int y = int(i) - 7;
    std::snprintf(buf, sizeof buf, "%.17g %.17g %d %d", z, x, int(i % 256), y);
    lines += std::string(buf) + "\n";
    paired += std::string(buf) + (i % 2 ? "\n" : " ");
    want.insert(want.end(), {x, double(y), z});
  }
  if (n % 2) paired += "\n";
  for (std::size_t i = 0; i + 2 < n; ++i) {
    const std::string f =
        "3 " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\n";
    lines += f;
    paired += f;
  }
  const auto a = io::parse_mesh(lines, ".ply", "a.ply");
  const auto b = io::parse_mesh(paired, ".ply", "b.ply");
  EXPECT_EQ(a.coords, want);
  EXPECT_EQ(a.coords, b.coords);
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_EQ(a.cells.size(), 3 * (n - 2));
  // a bad token on line L of the file: the same message, line L
  const std::int64_t header_lines = 10;
  for (std::size_t bad : {std::size_t(5), n / 2, n - 1}) {
    std::string t = lines;
    std::size_t at = 0;
    for (std::int64_t l = 1; l < header_lines + std::int64_t(bad) + 1; ++l)
      at = t.find('\n', at) + 1;
    t.replace(at, t.find(' ', at) - at, "oops");
    try {
      io::parse_mesh(t, ".ply", "c.ply");
      ADD_FAILURE() << "accepted a bad token";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "c.ply:" + std::to_string(header_lines + bad + 1) +
                                           ": expected a number, found 'oops'");
    }
  }
}

TEST(Io, PlyBigEndianAndFloat) {
  // Hand-made binary big-endian PLY with float x,y,z and an extra property.
  std::string s =
      "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nend_header\n";
  auto put = [&](float f) {
    unsigned char b[4];
    std::memcpy(b, &f, 4);
    for (int i = 3; i >= 0; --i) s += char(b[i]);
  };
  put(1.5f), put(-2.0f), put(0.25f), s += char(7);
  put(3.0f), put(4.0f), put(5.0f), s += char(9);
  auto p = io::parse_points(s, ".ply", "be.ply");
  EXPECT_EQ(p.coords, (std::vector<double>{1.5, -2.0, 0.25, 3, 4, 5}));
}

TEST(Io, NpyFloat32Points) {
  io::Grid g;  // write a float32 N x 3 array through the grid writer, read as points
  g.shape = {4, 3};
  g.type = io::ScalarType::F32;
  std::vector<float> v{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11.5f};
  g.data.assign(reinterpret_cast<unsigned char*>(v.data()),
                reinterpret_cast<unsigned char*>(v.data() + 12));
  io::write_grid(path("f32.npy"), g);
  auto p = io::read_points(path("f32.npy"));
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords.back(), 11.5);
}

TEST(Io, MeshRoundTrips) {
  io::Mesh tri;
  tri.dim = 2;
  tri.coords = {0, 0, 1, 0, 0, 1, 1, 1};
  tri.cell_size = 3;
  tri.cells = {0, 1, 2, 1, 3, 2};
  io::Mesh tet;
  tet.dim = 3;
  tet.coords = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  tet.cell_size = 4;
  tet.cells = {0, 1, 2, 3, 1, 2, 3, 4};
  for (std::string ext : {".ply", ".off", ".obj", ".ele", ".vtu", ".vtk", ".npy"})
    for (const io::Mesh* m : {&tri, &tet}) {
      const std::string f = path("m" + std::to_string(m->cell_size) + ext);
      if ((ext == ".off" || ext == ".obj") && m->cell_size == 4) {
        EXPECT_THROW(io::write_mesh(f, *m), Error);
        continue;
      }
      io::write_mesh(f, *m);
      auto r = io::read_mesh(f);
      EXPECT_EQ(r.cells, m->cells) << ext;
      EXPECT_EQ(r.cell_size, m->cell_size) << ext;
      if (ext == ".npy") continue;  // cells only
      std::vector<double> want(m->coords.begin(), m->coords.end());
      if ((ext == ".off" || ext == ".obj") && m->dim == 2) {  // 3D formats pad z = 0
        want.clear();
        for (std::size_t i = 0; i < m->coords.size(); i += 2)
          want.insert(want.end(), {m->coords[i], m->coords[i + 1], 0});
      }
      EXPECT_EQ(r.coords, want) << ext;
    }
  EXPECT_TRUE(no_temp_files());
}

// Gmsh 2.2 ascii (written only): nodes numbered from 1 with z = 0 for 2D, triangles (type 2)
// and tetrahedra (type 4), region tags from an integer "attribute" cell array, else 1.
TEST(Io, MshWritten) {
  io::Mesh tri;
  tri.dim = 2;
  tri.coords = {0, 0, 1, 0, 0, 1, 1, 1};
  tri.cells = {0, 1, 2, 1, 3, 2};
  const double attr[2] = {3, 7};
  tri.cell_data.push_back(io::make_data_array("attribute", io::ScalarType::F64, 1, attr, 2));
  io::write_mesh(path("m.msh"), tri);
  std::ifstream in(path("m.msh"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text,
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
            "4 1 1 0\n$EndNodes\n$Elements\n2\n1 2 2 3 3 1 2 3\n2 2 2 7 7 2 4 3\n"
            "$EndElements\n");
  io::Mesh tet;
  tet.dim = 3;
  tet.coords = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.5};
  tet.cell_size = 4;
  tet.cells = {0, 1, 2, 3};
  const double frac[1] = {0.5};  // not an integer: every tag 1
  tet.cell_data.push_back(io::make_data_array("attribute", io::ScalarType::F64, 1, frac, 1));
  io::write_mesh(path("t.msh"), tet);
  std::ifstream in2(path("t.msh"));
  const std::string t2((std::istreambuf_iterator<char>(in2)), std::istreambuf_iterator<char>());
  EXPECT_NE(t2.find("4 0 0 0.5\n"), std::string::npos);
  EXPECT_NE(t2.find("\n1 4 2 1 1 1 2 3 4\n"), std::string::npos);
  EXPECT_THROW(io::read_mesh(path("t.msh")), Error);  // written only
  EXPECT_TRUE(no_temp_files());
}

// VTU in each encoding gpugeom writes: binary (raw appended), zlib-compressed (blocks of
// 1 MiB: the large mesh spans several), ascii; doubles bit for bit, including values whose
// shortest text is long.
TEST(Io, VtuEncodingsRoundTrip) {
  const auto pts = generate3d("ball", 300000, 3);  // 7.2 MB of coordinates: 7 zlib blocks
  io::Mesh big;
  big.dim = 3;
  for (const auto& q : pts) big.coords.insert(big.coords.end(), {q.x, q.y, q.z});
  big.cell_size = 4;
  for (std::int32_t i = 0; i + 3 < std::int32_t(pts.size()); i += 2)
    big.cells.insert(big.cells.end(), {i, i + 1, i + 2, i + 3});
  io::Mesh small;
  small.dim = 2;
  small.coords = {0.1, -2.5e-7, 3.0, 1.0 / 3.0, -0.0, 1e-300, 5e300, 2};
  small.cell_size = 3;
  small.cells = {0, 1, 2, 1, 3, 2};
  std::uintmax_t raw_size = 0;
  for (const io::Mesh* m : {&small, &big})
    for (int mode = 0; mode < 3; ++mode) {
      io::WriteOptions o;
      o.binary = mode != 2;
      o.compress = mode == 1;
      const std::string f = path("enc" + std::to_string(mode) + ".vtu");
      io::write_mesh(f, *m, o);
      const auto r = io::read_mesh(f);
      EXPECT_EQ(r.dim, m->dim) << mode;
      EXPECT_EQ(r.cells, m->cells) << mode;
      ASSERT_EQ(r.coords.size(), m->coords.size()) << mode;
      EXPECT_EQ(std::memcmp(r.coords.data(), m->coords.data(), 8 * r.coords.size()), 0) << mode;
      if (mode == 0) raw_size = fs::file_size(f);
      if (m == &big && mode == 1)  // (random doubles hardly compress; the cells do)
        EXPECT_LT(fs::file_size(f), raw_size);
    }
  EXPECT_TRUE(no_temp_files());
}

// Point and cell data arrays of every type go out and come back bit for bit in each encoding;
// arrays of the wrong length are refused before anything is written.
TEST(Io, VtuDataArraysRoundTrip) {
  io::Mesh m;
  m.dim = 3;
  const std::size_t nv = 5000, nc = 3000;
  for (std::size_t i = 0; i < 3 * nv; ++i) m.coords.push_back(std::sin(double(i)) * 1e3);
  m.cell_size = 4;
  for (std::size_t c = 0; c < nc; ++c)
    for (int j = 0; j < 4; ++j) m.cells.push_back(std::int32_t((c + std::size_t(j)) % nv));
  std::vector<std::int32_t> dup(nv);
  std::vector<double> dist(nv);
  std::vector<float> vec(3 * nc);
  std::vector<std::uint8_t> flag(nc);
  std::vector<std::int64_t> big(nc);
  for (std::size_t i = 0; i < nv; ++i) {
    dup[i] = i % 7 ? -1 : std::int32_t(i / 7);
    dist[i] = 1.0 / (1.0 + double(i)) - 1e-300;
  }
  for (std::size_t c = 0; c < nc; ++c) {
    vec[3 * c] = float(c) * 0.1f;
    vec[3 * c + 1] = -float(c);
    vec[3 * c + 2] = 1e-30f;
    flag[c] = std::uint8_t(c % 251);
    big[c] = std::int64_t(c) * 1'000'000'007LL - 5;
  }
  m.point_data = {io::make_data_array("duplicate_of", io::ScalarType::I32, 1, dup.data(), nv),
                  io::make_data_array("distance", io::ScalarType::F64, 1, dist.data(), nv)};
  m.cell_data = {io::make_data_array("vector", io::ScalarType::F32, 3, vec.data(), 3 * nc),
                 io::make_data_array("flag", io::ScalarType::U8, 1, flag.data(), nc),
                 io::make_data_array("id", io::ScalarType::I64, 1, big.data(), nc)};
  for (int mode = 0; mode < 3; ++mode) {
    SCOPED_TRACE(mode);
    io::WriteOptions o;
    o.binary = mode != 2;
    o.compress = mode == 1;
    const std::string f = path("data" + std::to_string(mode) + ".vtu");
    io::write_mesh(f, m, o);
    const auto r = io::read_mesh(f);
    EXPECT_EQ(r.cells, m.cells);
    ASSERT_EQ(r.point_data.size(), 2u);
    ASSERT_EQ(r.cell_data.size(), 3u);
    for (int sec = 0; sec < 2; ++sec) {
      const auto& want = sec ? m.cell_data : m.point_data;
      const auto& got = sec ? r.cell_data : r.point_data;
      for (std::size_t k = 0; k < want.size(); ++k) {
        EXPECT_EQ(got[k].name, want[k].name);
        EXPECT_EQ(got[k].type, want[k].type);
        EXPECT_EQ(got[k].components, want[k].components);
        EXPECT_EQ(got[k].bytes, want[k].bytes) << want[k].name;
      }
    }
  }
  io::Mesh bad = m;
  bad.cell_data[1].bytes.pop_back();
  try {
    io::write_mesh(path("bad.vtu"), bad);
    ADD_FAILURE() << "accepted a cell data array of the wrong length";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
    EXPECT_NE(std::string(e.what()).find("flag"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path("bad.vtu")));
  EXPECT_TRUE(no_temp_files());
}

// VTK legacy files: ours round-trip (BINARY and ASCII, with point and cell data); files in the
// layouts other writers use are read (5.1 OFFSETS / CONNECTIVITY, VECTORS, FIELD, METADATA,
// LOOKUP_TABLE); malformed ones are Parse errors with a line.
TEST(Io, VtkLegacy) {
  io::Mesh m;
  m.dim = 3;
  m.coords = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1.0 / 3, 1e-300, -5e300};
  m.cell_size = 4;
  m.cells = {0, 1, 2, 3, 1, 2, 3, 4};
  const std::int32_t dup[5] = {-1, -1, 0, -1, 2};
  const float vec[6] = {0.5f, -1, 2, 1e-30f, 3, 4};
  const double h[5] = {0.1, 0.2, 1.0 / 3, -7, 1e300};
  m.point_data = {io::make_data_array("duplicate_of", io::ScalarType::I32, 1, dup, 5),
                  io::make_data_array("height", io::ScalarType::F64, 1, h, 5)};
  m.cell_data = {io::make_data_array("vec", io::ScalarType::F32, 3, vec, 6)};
  for (bool binary : {true, false}) {
    io::WriteOptions o;
    o.binary = binary;
    io::write_mesh(path("m.vtk"), m, o);
    const auto r = io::read_mesh(path("m.vtk"));
    EXPECT_EQ(r.coords, m.coords) << binary;
    EXPECT_EQ(r.cells, m.cells) << binary;
    ASSERT_EQ(r.point_data.size(), 2u);
    ASSERT_EQ(r.cell_data.size(), 1u);
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(r.point_data[k].name, m.point_data[k].name);
      EXPECT_EQ(r.point_data[k].bytes, m.point_data[k].bytes) << binary << k;
    }
    EXPECT_EQ(r.cell_data[0].components, 3);
    EXPECT_EQ(r.cell_data[0].bytes, m.cell_data[0].bytes) << binary;
  }
  // Version 5.1 as VTK 9 writes it (ASCII), triangles, with the attribute kinds others write.
  const std::string v51 =
      "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 4 float\n0 0 0 1 0 0\n0 1 0 1 1 0\n\n"
      "METADATA\nINFORMATION 0\n\n"
      "CELLS 3 6\nOFFSETS vtktypeint64\n0 3 6\nCONNECTIVITY vtktypeint64\n0 1 2 1 3 2\n"
      "CELL_TYPES 2\n5\n5\n\n"
      "POINT_DATA 4\nSCALARS temp double\nLOOKUP_TABLE default\n1.5 2.5 3.5 4.5\n"
      "VECTORS velocity float\n1 0 0 0 1 0 0 0 1 1 1 1\n"
      "CELL_DATA 2\nFIELD FieldData 2\nregion 1 2 int\n7 9\nflag 2 2 unsigned_char\n1 0 0 1\n";
  const auto a = io::parse_mesh(v51, ".vtk", "v51.vtk");
  EXPECT_EQ(a.dim, 2);
  EXPECT_EQ(a.cells, (std::vector<std::int32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(a.coords, (std::vector<double>{0, 0, 1, 0, 0, 1, 1, 1}));
  ASSERT_EQ(a.point_data.size(), 2u);
  EXPECT_EQ(a.point_data[1].name, "velocity");
  EXPECT_EQ(a.point_data[1].components, 3);
  ASSERT_EQ(a.cell_data.size(), 2u);
  EXPECT_EQ(a.cell_data[0].type, io::ScalarType::I32);
  EXPECT_EQ(a.cell_data[1].type, io::ScalarType::U8);
  EXPECT_EQ(a.cell_data[1].count(), 4u);
  // Version 5.1 BINARY (big-endian), built here byte by byte.
  std::string b51 =
      "# vtk DataFile Version 5.1\nx\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n";
  auto be = [&](auto v) {
    unsigned char raw[sizeof v];
    std::memcpy(raw, &v, sizeof v);
    for (std::size_t i = sizeof v; i-- > 0;) b51 += char(raw[i]);
  };
  for (double v : {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0}) be(v);
  b51 += "\nCELLS 3 6\nOFFSETS vtktypeint64\n";
  for (std::int64_t v : {0, 3, 6}) be(v);
  b51 += "\nCONNECTIVITY vtktypeint64\n";
  for (std::int64_t v : {0, 1, 2, 1, 3, 2}) be(v);
  b51 += "\nCELL_TYPES 2\n";
  for (std::int32_t v : {5, 5}) be(v);
  b51 += "\n";
  const auto bb = io::parse_mesh(b51, ".vtk", "b51.vtk");
  EXPECT_EQ(bb.cells, a.cells);
  EXPECT_EQ(bb.coords, a.coords);
  // Malformed: each a Parse error naming the file.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\n", "UNSTRUCTURED_GRID"},
      {"hello\n", "not a VTK legacy file"},
      {"# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 99999999999 "
       "double\n1 2 3\n",
       "ends before"},
      {"# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 "
       "0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 7\nCELL_TYPES 1\n5\n",
       "missing point"},
      {"# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 "
       "0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n9\n",
       "cell types"},
      {"# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 "
       "0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\nPOINT_DATA 4\n",
       "the mesh has 3"},
      {"# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 bit\n",
       "unsupported data type"},
      {"# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 "
       "0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\nCELL_DATA 1\nSCALARS n int\n3e18\n",
       "outside the range of its type"}};
  for (const auto& [text, what] : bad) {
    try {
      io::parse_mesh(text, ".vtk", "bad.vtk");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::Parse) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("bad.vtk:", 0), 0u) << e.what();
    }
  }
  EXPECT_TRUE(no_temp_files());
}

// Files written by another implementation (Python's struct, base64 and zlib:
// tests/io/make_vtu_fixtures.py), one per encoding VTU files come in.
TEST(Io, VtuReadsEveryEncoding) {
  const std::vector<double> tri = {0.1, -2.5e-7, 3.0, 0.25, -1.5, 7.0, 2.0, 2.0};
  const std::vector<std::int32_t> tri_cells = {0, 1, 2, 1, 3, 2};
  const std::vector<double> tet = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1.5};
  const std::vector<std::int32_t> tet_cells = {0, 1, 2, 3, 1, 2, 3, 4};
  int seen = 0;
  for (const auto& e : fs::directory_iterator(GG_IO_DATA)) {
    if (e.path().extension() != ".vtu") continue;
    ++seen;
    const std::string f = e.path().string(), stem = e.path().stem().string();
    SCOPED_TRACE(stem);
    const auto m = io::read_mesh(f);
    if (stem.rfind("tri", 0) == 0) {
      EXPECT_EQ(m.dim, 2);
      EXPECT_EQ(m.cell_size, 3);
      EXPECT_EQ(m.cells, tri_cells);
      std::vector<double> want = tri;
      if (stem.find("f32") != std::string::npos)
        for (auto& v : want) v = double(float(v));
      EXPECT_EQ(m.coords, want);
    } else {
      EXPECT_EQ(m.dim, 3);
      EXPECT_EQ(m.cell_size, 4);
      EXPECT_EQ(m.cells, tet_cells);
      EXPECT_EQ(m.coords, tet);
    }
    // The point and cell data every fixture carries, in their own types.
    ASSERT_EQ(m.point_data.size(), 1u);
    ASSERT_EQ(m.cell_data.size(), 2u);
    const io::DataArray &h = m.point_data[0], &reg = m.cell_data[0], &nrm = m.cell_data[1];
    EXPECT_EQ(h.name, "height");
    EXPECT_EQ(h.type, io::ScalarType::F64);
    ASSERT_EQ(h.count(), m.num_vertices());
    for (std::size_t i = 0; i < h.count(); ++i) {
      double v;
      std::memcpy(&v, h.bytes.data() + 8 * i, 8);
      EXPECT_EQ(v, 0.5 * double(i) - 1.25);
    }
    EXPECT_EQ(reg.name, "region");
    EXPECT_EQ(reg.type, io::ScalarType::I32);
    ASSERT_EQ(reg.count(), m.num_cells());
    for (std::size_t i = 0; i < reg.count(); ++i) {
      std::int32_t v;
      std::memcpy(&v, reg.bytes.data() + 4 * i, 4);
      EXPECT_EQ(v, 7 * std::int32_t(i) - 3);
    }
    EXPECT_EQ(nrm.name, "normal");
    EXPECT_EQ(nrm.type, io::ScalarType::F32);
    EXPECT_EQ(nrm.components, 3);
    ASSERT_EQ(nrm.count(), 3 * m.num_cells());
    float nv[3];
    std::memcpy(nv, nrm.bytes.data(), 12);
    EXPECT_EQ(nv[0], 0.5f);
    EXPECT_EQ(nv[1], -1.0f);
    EXPECT_EQ(nv[2], 2.0f);
  }
  EXPECT_EQ(seen, 12);
}

// Broken VTU files: each a Parse error naming the problem, never a crash or a huge allocation.
TEST(Io, VtuMalformed) {
  const std::string ok = R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt32">
<UnstructuredGrid><Piece NumberOfPoints="3" NumberOfCells="1"><Points>
<DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0</DataArray>
</Points><Cells>
<DataArray type="Int32" Name="connectivity" format="ascii">0 1 2</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">3</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">5</DataArray>
</Cells></Piece></UnstructuredGrid></VTKFile>
)";
  EXPECT_EQ(io::parse_mesh(ok, ".vtu", "ok").cells.size(), 3u);
  auto fails = [&](const std::string& body, const std::string& what) {
    try {
      io::parse_mesh(body, ".vtu", "bad.vtu");
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::Parse) << what;
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted: " << what;
  };
  auto with = [&](const std::string& from, const std::string& to) {
    std::string b = ok;
    b.replace(b.find(from), from.size(), to);
    return b;
  };
  fails(with("UnstructuredGrid\"", "PolyData\""), "not a VTK UnstructuredGrid");
  fails(with("Float64", "Float128"), "unsupported DataArray type");
  fails(with("0 1 2</", "0 1 7</"), "missing point");
  fails(with("format=\"ascii\">3<", "format=\"ascii\">4<"), "unexpected offsets");
  fails(with(">5<", ">9<"), "cell types");
  fails(with("header_type=\"UInt32\"", "header_type=\"UInt16\""), "header_type");
  // appended data whose header claims more than is there, and a zlib header claiming 2^40 bytes
  const std::string app =
      with("format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>", "format=\"appended\" offset=\"0\"/>");
  std::string cut = app;  // a block claiming 65535 bytes with 3 there
  std::string tail = "<AppendedData encoding=\"raw\">_";
  tail += std::string("\xff\xff\x00\x00", 4) + "abc</AppendedData>";
  cut.replace(cut.find("</UnstructuredGrid>"), 19, "</UnstructuredGrid>" + tail);
  fails(cut, "ends before");
  std::string z = app;
  z.replace(z.find("header_type=\"UInt32\""), 20,
            "header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\"");
  std::string zt = "<AppendedData encoding=\"raw\">_";
  const std::uint32_t words[4] = {1, 0x40000000u, 0x40000000u, 8};
  zt += std::string(reinterpret_cast<const char*>(words), 16) + "12345678</AppendedData>";
  z.replace(z.find("</UnstructuredGrid>"), 19, "</UnstructuredGrid>" + zt);
  fails(z, "out of range");
  // compressed sizes whose sum wraps around 2^64 (found by the fuzzer)
  std::string w = app;
  w.replace(w.find("header_type=\"UInt32\""), 20,
            "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"");
  std::string wt = "<AppendedData encoding=\"raw\">_";
  const std::uint64_t wwords[5] = {2, 16, 16, ~std::uint64_t(0), 9};
  wt += std::string(reinterpret_cast<const char*>(wwords), 40) + "123456789</AppendedData>";
  w.replace(w.find("</UnstructuredGrid>"), 19, "</UnstructuredGrid>" + wt);
  fails(w, "ends before");
  fails(with("format=\"ascii\">0 1 2<", "format=\"binary\">!!!!!!!!!!!!<"), "base64");
}

TEST(Io, GridRoundTrips) {
  io::Grid g;
  g.shape = {5, 7};
  g.type = io::ScalarType::U8;
  for (int i = 0; i < 35; ++i) g.data.push_back(std::uint8_t(i * 7));
  for (std::string ext : {".png", ".pgm", ".npy"}) {
    io::write_grid(path("g" + ext), g);
    auto r = io::read_grid(path("g" + ext));
    EXPECT_EQ(r.shape, g.shape) << ext;
    EXPECT_EQ(r.data, g.data) << ext;
  }
  io::Grid w = g;  // 16-bit
  w.type = io::ScalarType::U16;
  w.data.clear();
  for (int i = 0; i < 35; ++i) {
    std::uint16_t v = std::uint16_t(i * 1871);
    w.data.push_back(v & 0xff), w.data.push_back(v >> 8);
  }
  for (std::string ext : {".png", ".pgm", ".npy"}) {
    io::write_grid(path("w" + ext), w);
    auto r = io::read_grid(path("w" + ext));
    EXPECT_EQ(int(r.type), int(io::ScalarType::U16)) << ext;
    EXPECT_EQ(r.data, w.data) << ext;
  }
  io::Grid b = g;  // bitmap
  for (auto& v : b.data) v = v % 3 == 0;
  io::write_grid(path("b.pbm"), b);
  EXPECT_EQ(io::read_grid(path("b.pbm")).data, b.data);
  io::Grid v3;  // 3D volumes of every type through npy and raw
  v3.shape = {3, 4, 5};
  for (auto t : {io::ScalarType::Bool, io::ScalarType::U8, io::ScalarType::U16, io::ScalarType::I32,
                 io::ScalarType::I64, io::ScalarType::F32, io::ScalarType::F64}) {
    v3.type = t;
    v3.data.assign(60 * io::scalar_size(t), 0);
    for (std::size_t i = 0; i < v3.data.size(); i += io::scalar_size(t))
      v3.data[i] = std::uint8_t(i % 2);
    io::write_grid(path("v.npy"), v3);
    EXPECT_EQ(io::read_grid(path("v.npy")).data, v3.data) << io::scalar_name(t);
    io::write_grid(path("v.raw"), v3);
    EXPECT_EQ(io::read_raw_grid(path("v.raw"), v3.shape, t).data, v3.data);
  }
  EXPECT_THROW(io::read_raw_grid(path("v.raw"), {3, 4, 6}, io::ScalarType::F64), Error);
  EXPECT_TRUE(no_temp_files());
}

// The readers' fast path (numbers scanned straight from a line) and their token path (which
// makes the error messages) agree: lines of every form either path takes give the values
// strtod gives, and lines the fast path refuses fail with the token path's message.
TEST(Io, FastScanAndTokenPathAgree) {
  const std::vector<std::string> good = {
      "1 2 3",   "+1.5 -2e3 3",        "\t1\t2\t3\r", "1,2,3",        "1, 2 ,3",
      "1,,2,,3", "1e-300 -0 4.9e-324", "inf -inf 5",  "  7   8   9  "};
  std::string xyz;
  for (const auto& l : good) xyz += l + "\n";
  std::vector<double> want;
  for (const auto& l : good) {
    std::string t = l;
    for (char& c : t)
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    std::istringstream in(t);
    for (std::string w; in >> w;) want.push_back(std::strtod(w.c_str(), nullptr));
  }
  for (const char* ext : {".xyz", ".csv"}) {
    const io::PointSet p = io::parse_points(xyz, ext, "g.xyz");
    ASSERT_EQ(p.dim, 3) << ext;
    ASSERT_EQ(p.coords.size(), want.size()) << ext;
    for (std::size_t i = 0; i < want.size(); ++i)
      EXPECT_EQ(std::memcmp(&p.coords[i], &want[i], 8), 0) << ext << " value " << i;
  }
  // Refused by the fast path: the token path's messages, on the right line.
  const std::pair<const char*, const char*> bad[] = {
      {"1 2 3\n4 5 0x\n", "b.xyz:2: expected a number for a coordinate, found '0x'"},
      {"1 2 3\n4 5 6 # c\n", "b.xyz:2: expected 3 coordinates (as on the first line), found 5"},
      {"1 2 3\n4 5\n", "b.xyz:2: expected 3 coordinates (as on the first line), found 2"},
      {"1 2 3\n4 5 6e\n", "b.xyz:2: expected a number for a coordinate, found '6e'"},
      {"1 2 3\n4 ++5 6\n", "b.xyz:2: expected a number for a coordinate, found '++5'"}};
  for (const auto& [text, msg] : bad)
    EXPECT_EQ(expect_parse_error([&] { io::parse_points(text, ".xyz", "b.xyz"); }), msg);
  // .node (extra attribute columns allowed), .off faces with colours, .ele ranges.
  const io::PointSet n =
      io::parse_points("3 2 1 0\n0 0.5 1.5 7\n1 +2 -3 8\n2 1e3 4 9\n", ".node", "a.node");
  EXPECT_EQ(n.coords, (std::vector<double>{0.5, 1.5, 2, -3, 1e3, 4}));
  EXPECT_EQ(
      expect_parse_error([] { io::parse_points("2 2 0 0\n0 1 1\n1 1 x\n", ".node", "a.node"); }),
      "a.node:3: expected a number for a coordinate, found 'x'");
  const io::Mesh off =
      io::parse_mesh("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n", ".off", "c.off");
  EXPECT_EQ(off.cells, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_NE(expect_parse_error([] {
              io::parse_mesh("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 2 3\n", ".off",
                             "q.off");
            }).find("q.off:7: face 0 is not a triangle"),
            std::string::npos);
}

TEST(Io, MalformedInputsNameFileLineAndWhat) {
  std::string m;
  m = expect_parse_error([] { io::parse_points("1 2 3\n4 5\n", ".xyz", "a.xyz"); });
  EXPECT_NE(m.find("a.xyz:2"), std::string::npos) << m;
  m = expect_parse_error([] { io::parse_points("1 2 3\n4 five 6\n", ".xyz", "a.xyz"); });
  EXPECT_NE(m.find("'five'"), std::string::npos) << m;
  m = expect_parse_error([] { io::parse_points("", ".xyz", "e.xyz"); });
  m = expect_parse_error([] { io::parse_points("plx\n", ".ply", "a.ply"); });
  EXPECT_NE(m.find("a.ply:1"), std::string::npos) << m;
  m = expect_parse_error([] {
    io::parse_points(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
        "y\nend_header\n1 2\n",
        ".ply", "t.ply");
  });
  EXPECT_NE(m.find("ends early"), std::string::npos) << m;
  m = expect_parse_error([] {
    io::parse_points(
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty double x\n"
        "property double y\nend_header\n12345678",
        ".ply", "huge.ply");
  });
  EXPECT_NE(m.find("claims"), std::string::npos) << m;
  m = expect_parse_error([] {
    io::parse_points("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n",
                     ".ply", "nox.ply");
  });
  EXPECT_NE(m.find("x and y"), std::string::npos) << m;
  // Found by the fuzzer: repeated elements or properties must not confuse the vertex layout.
  m = expect_parse_error([] {
    io::parse_points(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "element vertex 1\nproperty float z\nproperty float x\nend_header\n1 2\n3 4\n",
        ".ply", "d.ply");
  });
  EXPECT_NE(m.find("declared twice"), std::string::npos) << m;
  m = expect_parse_error([] {
    io::parse_points(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n"
        "property float y\nend_header\n1 2 3\n",
        ".ply", "p.ply");
  });
  EXPECT_NE(m.find("twice"), std::string::npos) << m;
  {  // Found by the fuzzer: an element without properties claiming 1.7e18 items hung the reader.
    const auto p = io::parse_points(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "element junk 1696801028708149930\nend_header\n1 2\n",
        ".ply", "empty_element.ply");
    EXPECT_EQ(p.coords, (std::vector<double>{1, 2}));
  }
  m = expect_parse_error([] { io::parse_points("OFF\n2 0 0\n1 2 3\n", ".off", "a.off"); });
  EXPECT_NE(m.find("1 of 2"), std::string::npos) << m;
  m = expect_parse_error([] { io::parse_points("v 1 2\n", ".obj", "a.obj"); });
  m = expect_parse_error([] { io::parse_points("3 2 0 0\n0 1 1\n1 2 2\n", ".node", "a.node"); });
  m = expect_parse_error([] { io::parse_points("\x93NUMPY\x01", ".npy", "a.npy"); });
  m = expect_parse_error([] {
    std::string h = "{'descr': '<f8', 'fortran_order': False, 'shape': (10, 3), }";
    std::string s = std::string("\x93NUMPY\x01\x00", 8) + char(h.size()) + char(0) + h + "abc";
    io::parse_points(s, ".npy", "short.npy");
  });
  EXPECT_NE(m.find("truncated"), std::string::npos) << m;
  m = expect_parse_error([] {
    std::string h = "{'descr': '<c16', 'fortran_order': False, 'shape': (1, 3), }";
    io::parse_points(std::string("\x93NUMPY\x01\x00", 8) + char(h.size()) + char(0) + h, ".npy",
                     "c.npy");
  });
  EXPECT_NE(m.find("dtype"), std::string::npos) << m;
  m = expect_parse_error(
      [] { io::parse_mesh("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", ".off", "f.off"); });
  EXPECT_NE(m.find("out of range"), std::string::npos) << m;
  m = expect_parse_error([] { io::parse_grid("P5\n4 4\n255\nab", ".pgm", "g.pgm"); });
  EXPECT_NE(m.find("truncated"), std::string::npos) << m;
  m = expect_parse_error([] { io::parse_grid("\x89PNG\r\n\x1a\nbroken", ".png", "g.png"); });
  EXPECT_NE(m.find("g.png"), std::string::npos) << m;
  // Found by the fuzzer: a line of blanks and carriage returns is blank, not a token-less line.
  auto obj = io::parse_mesh("v 0 0 0\n  \r\r \nv 1 0 0\nv 0 1 0\nf 1 2 3\n", ".obj", "cr.obj");
  EXPECT_EQ(obj.cells.size(), 3u);
  EXPECT_THROW(io::parse_mesh("   \r\r\r ", ".obj", "cr.obj"), Error);
  EXPECT_THROW(io::read_points(path("does-not-exist.xyz")), Error);
  EXPECT_THROW(io::parse_points("1 2\n", ".abc", "x.abc"), Error);
}

// Found by the fuzzer: integer arrays used to pass through a double (lossy above 2^53, and
// undefined for uint64 values above 2^63).
TEST(Io, NpyIntegersAreExact) {
  auto npy = [](const std::string& descr, const std::string& payload) {
    std::string h = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (1, 2), }";
    return std::string("\x93NUMPY\x01\x00", 8) + char(h.size()) + char(0) + h + payload;
  };
  std::string big(16, '\0');  // int64 2^62 + 1 and -3, little endian
  const std::int64_t vals[2] = {(std::int64_t(1) << 62) + 1, -3};
  std::memcpy(&big[0], vals, 16);
  auto g = io::parse_grid(npy("<i8", big), ".npy", "i8.npy");
  std::int64_t back[2];
  std::memcpy(back, g.data.data(), 16);
  EXPECT_EQ(back[0], vals[0]);
  EXPECT_EQ(back[1], vals[1]);
  auto be =
      io::parse_grid(npy(">i2", std::string("\xff\xfe\x00\x07", 4)), ".npy", "be.npy");  // -2, 7
  EXPECT_EQ(be.value(0), -2);
  EXPECT_EQ(be.value(1), 7);
  expect_parse_error(
      [&] { io::parse_grid(npy("<u8", std::string(16, '\xff')), ".npy", "u8.npy"); });
}

TEST(Io, FailedWriteLeavesNothing) {
  io::PointSet p = sample(3, 10);
  EXPECT_THROW(io::write_points(tmpdir() + "/no/such/dir/p.xyz", p), Error);
  EXPECT_FALSE(fs::exists(tmpdir() + "/no"));
  io::Mesh bad;
  bad.dim = 3;
  bad.coords = {0, 0, 0};
  bad.cells = {0, 0, 5};
  EXPECT_THROW(io::write_mesh(path("bad.ply"), bad), Error);
  EXPECT_FALSE(fs::exists(path("bad.ply")));
  EXPECT_TRUE(no_temp_files());
}
