// gpugeom stipple: a stipple drawing of a photograph. The density is the image's darkness; the
// dots sit at the sites of its weighted centroidal Voronoi diagram, each dot's area the
// darkness of its cell (so the drawing keeps the tone), drawn as SVG and PNG.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "cvd_cli.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::cli {

namespace {

void write_svg(const std::string& path, std::int64_t rows, std::int64_t cols, const CvdResult& r,
               const HostVector<double>& radius) {
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(cols) +
       "\" height=\"" + std::to_string(rows) + "\" viewBox=\"0 0 " + std::to_string(cols) + " " +
       std::to_string(rows) +
       "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<g "
       "fill=\"black\">\n";
  char buf[96];
  for (std::int64_t i = 0; i < r.num_sites; ++i) {
    if (radius[i] <= 0) continue;
    std::snprintf(buf, sizeof buf, "<circle cx=\"%.3f\" cy=\"%.3f\" r=\"%.3f\"/>\n",
                  r.sites[2 * i] + 0.5, r.sites[2 * i + 1] + 0.5, radius[i]);
    s += buf;
  }
  s += "</g>\n</svg>\n";
  io::write_text(path, s);
}

// Anti-aliased discs on white, `scale` output pixels per image pixel.
void write_png(const std::string& path, std::int64_t rows, std::int64_t cols, int scale,
               const CvdResult& r, const HostVector<double>& radius) {
  const std::int64_t H = rows * scale, W = cols * scale;
  std::vector<float> white(std::size_t(H * W), 1.0f);
  for (std::int64_t i = 0; i < r.num_sites; ++i) {
    const double cx = (r.sites[2 * i] + 0.5) * scale, cy = (r.sites[2 * i + 1] + 0.5) * scale;
    const double rad = radius[i] * scale;
    if (rad <= 0) continue;
    const std::int64_t x0 = std::max<std::int64_t>(0, std::int64_t(cx - rad - 1));
    const std::int64_t x1 = std::min<std::int64_t>(W - 1, std::int64_t(cx + rad + 1));
    const std::int64_t y0 = std::max<std::int64_t>(0, std::int64_t(cy - rad - 1));
    const std::int64_t y1 = std::min<std::int64_t>(H - 1, std::int64_t(cy + rad + 1));
    for (std::int64_t y = y0; y <= y1; ++y)
      for (std::int64_t x = x0; x <= x1; ++x) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        const double cover = std::clamp(rad + 0.5 - d, 0.0, 1.0);
        white[y * W + x] *= float(1 - cover);
      }
  }
  std::vector<unsigned char> rgb(std::size_t(H * W * 3));
  for (std::int64_t i = 0; i < H * W; ++i)
    rgb[i * 3] = rgb[i * 3 + 1] = rgb[i * 3 + 2] = (unsigned char)std::lround(255 * white[i]);
  io::write_png_rgb(path, H, W, rgb);
}

}  // namespace

int cmd_stipple(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << "usage: gpugeom stipple IMAGE -n N -o OUT.svg [options]\n\n"
                 "A stipple drawing of a 2D image (.png .pgm .npy): N dots at the sites of the\n"
                 "weighted centroidal Voronoi diagram of the image's darkness, each dot's area\n"
                 "the darkness of its cell.\n\n"
                 "  -n N                  number of dots (default 20000)\n"
                 "  --png FILE.png        also draw it as a PNG\n"
                 "  --png-scale S         PNG pixels per image pixel (default 2)\n"
                 "  --gamma G             darkness^G (default 1; above 1 lightens mid-tones)\n"
                 "  --contrast C          darkness stretched about mid-grey (default 1)\n"
                 "  --invert              dots where the image is bright\n"
                 "  --ink F               dot area = F x cell darkness (default 0.6)\n"
              << kLloydHelp;
    return kOk;
  }
  std::string out, n = "20000", png, scale = "2", gamma = "1", contrast = "1", ink = "0.6";
  a.value("-o", out) || a.value("--output", out);
  a.value("-n", n);
  a.value("--png", png);
  a.value("--png-scale", scale);
  a.value("--gamma", gamma);
  a.value("--contrast", contrast);
  a.value("--ink", ink);
  StippleOptions o;
  o.invert = a.flag("--invert");
  o.backend = g.backend;
  read_lloyd_options(a, o);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one image");
  if (out.empty() || io::extension(out) != ".svg") throw UsageError("give -o OUT.svg");
  if (!png.empty() && io::extension(png) != ".png") throw UsageError("--png writes a .png file");
  o.gamma = to_real(gamma, "--gamma");
  o.contrast = to_real(contrast, "--contrast");
  o.ink = to_real(ink, "--ink");
  const int sc = int(to_count(scale, "--png-scale"));
  if (!(o.gamma > 0) || !(o.contrast > 0) || !(o.ink > 0))
    throw UsageError("gamma, contrast, ink must be > 0");
  if (sc < 1 || sc > 16) throw UsageError("--png-scale must be in 1..16");
  o.num_sites = to_count(n, "-n");
  io::Grid img;
  {
    Timer t(g, "read");
    img = io::read_grid(pos[0]);
  }
  if (img.shape.size() != 2) throw UsageError("stipple takes a 2D image");
  attach_progress(g, o);
  Stipple st;
  {
    Timer t(g, "lloyd");
    st = stipple(view_of(img), o);
  }
  const CvdResult& r = st.cvd;
  const HostVector<double>& radius = st.radius;
  finish_progress(g, r);
  {
    Timer t(g, "write");
    write_svg(out, img.shape[0], img.shape[1], r, radius);
    if (!png.empty()) write_png(png, img.shape[0], img.shape[1], sc, r, radius);
  }
  if (!g.quiet)
    std::cout << "stipple " << pos[0] << ": " << r.num_sites << " dots, " << r.iterations
              << " iterations -> " << out << (png.empty() ? "" : " and " + png) << "\n";
  return kOk;
}

}  // namespace gpugeom::cli
