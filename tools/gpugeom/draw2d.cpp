// Drawings of 2D triangulations: SVG as vectors, PNG through a small anti-aliased line
// rasteriser (Wu's algorithm), both written atomically by the io module.
#include "draw2d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::cli {

std::vector<double> grown_box(const HostVector<double>& xy, double frac) {
  double b[4] = {xy[0], xy[1], xy[0], xy[1]};
  for (std::size_t i = 0; i < xy.size(); i += 2) {
    b[0] = std::min(b[0], xy[i]), b[2] = std::max(b[2], xy[i]);
    b[1] = std::min(b[1], xy[i + 1]), b[3] = std::max(b[3], xy[i + 1]);
  }
  double w = b[2] - b[0], h = b[3] - b[1];
  const double s = std::max(w, h) > 0 ? std::max(w, h) : 1.0;
  return {b[0] - frac * s, b[1] - frac * s, b[2] + frac * s, b[3] + frac * s};
}

namespace {

// Maps data coordinates to the picture (y up in the data, down in the picture).
struct View {
  double x0, y1, scale;
  int width, height;
  View(const std::vector<double>& box, int longer) {
    const double w = box[2] - box[0], h = box[3] - box[1];
    scale = longer / std::max(w, h);
    width = std::max(1, int(std::lround(w * scale)));
    height = std::max(1, int(std::lround(h * scale)));
    x0 = box[0];
    y1 = box[3];
  }
  double px(double x) const { return (x - x0) * scale; }
  double py(double y) const { return (y1 - y) * scale; }
};

template <class F>
void each_edge(const Triangulation2d& tri, F f) {  // every edge once
  const std::size_t nt = tri.num_triangles;
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t o = tri.neighbors[3 * t + k];
      if (o >= 0 && std::size_t(o) < t) continue;
      f(tri.triangles[3 * t + (k + 1) % 3], tri.triangles[3 * t + (k + 2) % 3]);
    }
}

template <class F>
void each_marked_edge(const Triangulation2d& tri, const std::int32_t* marks, F f) {
  if (!marks) return;
  const std::size_t nt = tri.num_triangles;
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t o = tri.neighbors[3 * t + k];
      if (marks[3 * t + k] < 0 || (o >= 0 && std::size_t(o) < t)) continue;
      f(tri.triangles[3 * t + (k + 1) % 3], tri.triangles[3 * t + (k + 2) % 3]);
    }
}

void svg(const std::string& path, const HostVector<double>& xy, const Triangulation2d& tri,
         const ClippedCells* cells, const std::int32_t* marks, const View& v) {
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                v.width, v.height);
  s += buf;
  s += "<g stroke=\"#888\" stroke-width=\"0.6\" fill=\"none\">\n";
  each_edge(tri, [&](std::int32_t a, std::int32_t b) {
    std::snprintf(buf, sizeof buf, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n",
                  v.px(xy[2 * a]), v.py(xy[2 * a + 1]), v.px(xy[2 * b]), v.py(xy[2 * b + 1]));
    s += buf;
  });
  s += "</g>\n";
  if (marks) {
    s += "<g stroke=\"#15c\" stroke-width=\"1.6\" fill=\"none\">\n";
    each_marked_edge(tri, marks, [&](std::int32_t a, std::int32_t b) {
      std::snprintf(buf, sizeof buf, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n",
                    v.px(xy[2 * a]), v.py(xy[2 * a + 1]), v.px(xy[2 * b]), v.py(xy[2 * b + 1]));
      s += buf;
    });
    s += "</g>\n";
  }
  if (cells) {
    s += "<g stroke=\"#d22\" stroke-width=\"0.8\" fill=\"none\">\n";
    for (std::size_t i = 0; i + 1 < cells->offsets.size(); ++i) {
      if (cells->offsets[i + 1] - cells->offsets[i] < 3) continue;
      s += "<polygon points=\"";
      for (std::int64_t j = cells->offsets[i]; j < cells->offsets[i + 1]; ++j) {
        std::snprintf(buf, sizeof buf, "%.2f,%.2f ", v.px(cells->xy[2 * j]),
                      v.py(cells->xy[2 * j + 1]));
        s += buf;
      }
      s += "\"/>\n";
    }
    s += "</g>\n";
  }
  s += "<g fill=\"black\">\n";
  for (std::size_t i = 0; i < xy.size(); i += 2) {
    std::snprintf(buf, sizeof buf, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"1.2\"/>\n", v.px(xy[i]),
                  v.py(xy[i + 1]));
    s += buf;
  }
  io::write_text(path, s + "</g>\n</svg>\n");
}

struct Canvas {
  int w, h;
  std::vector<float> r, g, b;  // coverage-blended colour, starts white
  Canvas(int w_, int h_) : w(w_), h(h_), r(std::size_t(w_) * h_, 1.f), g(r), b(r) {}
  void plot(int x, int y, float a, const float c[3]) {
    if (x < 0 || y < 0 || x >= w || y >= h || a <= 0) return;
    const std::size_t i = std::size_t(y) * w + x;
    r[i] += (c[0] - r[i]) * a, g[i] += (c[1] - g[i]) * a, b[i] += (c[2] - b[i]) * a;
  }
  void line(double x0, double y0, double x1, double y1, const float c[3]) {
    if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1))) return;
    const bool steep = std::fabs(y1 - y0) > std::fabs(x1 - x0);
    if (steep) std::swap(x0, y0), std::swap(x1, y1);
    if (x0 > x1) std::swap(x0, x1), std::swap(y0, y1);
    const double dx = x1 - x0, grad = dx > 0 ? (y1 - y0) / dx : 0;
    const int xa = std::max(0, int(std::floor(x0))),
              xb = std::min(steep ? h - 1 : w - 1, int(std::ceil(x1)));
    for (int x = xa; x <= xb; ++x) {
      const double y = y0 + grad * (x - x0);
      const int yi = int(std::floor(y));
      const float f = float(y - yi);
      if (steep)
        plot(yi, x, 1 - f, c), plot(yi + 1, x, f, c);
      else
        plot(x, yi, 1 - f, c), plot(x, yi + 1, f, c);
    }
  }
  void dot(double x, double y, double rad, const float c[3]) {
    for (int yy = int(y - rad - 1); yy <= int(y + rad + 1); ++yy)
      for (int xx = int(x - rad - 1); xx <= int(x + rad + 1); ++xx) {
        const double d = std::hypot(xx + 0.5 - x, yy + 0.5 - y);
        plot(xx, yy, float(std::clamp(rad + 0.5 - d, 0.0, 1.0)), c);
      }
  }
};

void png(const std::string& path, const HostVector<double>& xy, const Triangulation2d& tri,
         const ClippedCells* cells, const std::int32_t* marks, const View& v) {
  Canvas cv(v.width, v.height);
  const float grey[3] = {0.55f, 0.55f, 0.55f}, red[3] = {0.85f, 0.12f, 0.12f}, black[3] = {0, 0, 0},
              blue[3] = {0.08f, 0.33f, 0.8f};
  each_edge(tri, [&](std::int32_t a, std::int32_t b) {
    cv.line(v.px(xy[2 * a]), v.py(xy[2 * a + 1]), v.px(xy[2 * b]), v.py(xy[2 * b + 1]), grey);
  });
  each_marked_edge(tri, marks, [&](std::int32_t a, std::int32_t b) {
    for (double off : {-0.5, 0.0, 0.5})  // three lines: about 1.5 pixels wide
      cv.line(v.px(xy[2 * a]) + off, v.py(xy[2 * a + 1]) + off, v.px(xy[2 * b]) + off,
              v.py(xy[2 * b + 1]) + off, blue);
  });
  if (cells)
    for (std::size_t i = 0; i + 1 < cells->offsets.size(); ++i) {
      const std::int64_t a = cells->offsets[i], e = cells->offsets[i + 1];
      for (std::int64_t j = a; j < e; ++j) {
        const std::int64_t k = j + 1 < e ? j + 1 : a;
        cv.line(v.px(cells->xy[2 * j]), v.py(cells->xy[2 * j + 1]), v.px(cells->xy[2 * k]),
                v.py(cells->xy[2 * k + 1]), red);
      }
    }
  const double rad = xy.size() / 2 > 20000 ? 0.6 : 1.5;
  for (std::size_t i = 0; i < xy.size(); i += 2) cv.dot(v.px(xy[i]), v.py(xy[i + 1]), rad, black);
  std::vector<unsigned char> rgb(std::size_t(v.width) * v.height * 3);
  for (std::size_t i = 0; i < cv.r.size(); ++i) {
    rgb[3 * i] = (unsigned char)std::lround(255 * std::clamp(cv.r[i], 0.f, 1.f));
    rgb[3 * i + 1] = (unsigned char)std::lround(255 * std::clamp(cv.g[i], 0.f, 1.f));
    rgb[3 * i + 2] = (unsigned char)std::lround(255 * std::clamp(cv.b[i], 0.f, 1.f));
  }
  io::write_png_rgb(path, v.height, v.width, rgb);
}

}  // namespace

void draw_triangulation(const std::string& path, const HostVector<double>& xy,
                        const Triangulation2d& tri, const ClippedCells* cells,
                        const std::int32_t* marks) {
  const std::string ext = io::extension(path);
  if (ext != ".svg" && ext != ".png")
    throw UsageError("--draw writes .svg or .png, not '" + ext + "'");
  const View v(grown_box(xy, 0.05), 1600);
  if (ext == ".svg")
    svg(path, xy, tri, cells, marks, v);
  else
    png(path, xy, tri, cells, marks, v);
}

}  // namespace gpugeom::cli
