// Writes a synthetic benchmark case: a curved, unevenly stretched quad surface with holes (the
// bind), frames bent at a joint by two-bone linear blend skinning, and a patch file selecting
// every face but a one-quad border ring (so the writer also keeps untouched vertices).
//
//   skinslide_bench_case DIR VERTICES FRAMES
//
// Writes DIR/bind.obj, DIR/patch.txt and DIR/frames/f.NNNN.obj. Coordinates are written with 6
// decimals, as DCC exporters do. Deterministic: no random numbers.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

struct P3 {
  double x, y, z;
};

constexpr double kPi = 3.14159265358979323846;

// Holes: ellipses in the (s, t) parameter square, (centre s, centre t, radius s, radius t).
constexpr double kHoles[3][4] = {
    {0.30, 0.35, 0.06, 0.10}, {0.62, 0.62, 0.09, 0.05}, {0.75, 0.25, 0.04, 0.04}};

bool in_hole(double s, double t) {
  for (const auto& h : kHoles) {
    const double a = (s - h[0]) / h[2], b = (t - h[1]) / h[3];
    if (a * a + b * b < 1) return true;
  }
  return false;
}

// Bind: a half cylinder (radius 1, axis x, length 4) with spacing stretched along x and around.
P3 bind_point(double s, double t) {
  const double xs = s + 0.25 * s * (1 - s) * std::sin(3 * kPi * t);  // uneven, smooth spacing
  const double ang = kPi * (t + 0.1 * t * (1 - t));
  return {4 * xs - 2, std::cos(ang), std::sin(ang) * (1 + 0.15 * std::sin(2 * kPi * s))};
}

// Two-bone linear blend skinning: bone 1 rotates by `angle` about the z axis at the joint x = 0;
// the weight ramps over |x| < 0.6, which stretches the outside of the bend and bunches the inside.
P3 bend(const P3& p, double angle) {
  const double w = std::clamp((p.x + 0.6) / 1.2, 0.0, 1.0);
  const double ws = w * w * (3 - 2 * w);
  const double c = std::cos(angle), sn = std::sin(angle);
  const P3 r{c * p.x - sn * p.y, sn * p.x + c * p.y, p.z};
  return {(1 - ws) * p.x + ws * r.x, (1 - ws) * p.y + ws * r.y, p.z};
}

void append_fixed(std::string& out, double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed, 6);
  out.append(buf, r.ptr);
}

void write(const std::filesystem::path& path, const std::string& bytes) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fclose(f) != 0) {
    std::fprintf(stderr, "skinslide_bench_case: cannot write %s\n", path.c_str());
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: skinslide_bench_case DIR VERTICES FRAMES\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const long vertices = std::atol(argv[2]);
  const int frames = std::atoi(argv[3]);
  const int n =
      std::max(8, static_cast<int>(std::lround(std::sqrt(static_cast<double>(vertices)))));
  std::filesystem::create_directories(dir / "frames");

  // Grid vertices n x n; quads whose centre falls in a hole are dropped, then unused vertices.
  std::vector<std::array<long, 4>> quads;
  std::vector<int> border;  // 1 if the quad is on the outer ring
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const double s = (i + 0.5) / (n - 1), t = (j + 0.5) / (n - 1);
      if (in_hole(s, t)) continue;
      quads.push_back({j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i});
      border.push_back(i == 0 || j == 0 || i + 2 == n || j + 2 == n);
    }
  std::vector<long> id(static_cast<size_t>(n) * n, -1);
  std::vector<P3> bind;
  for (const auto& q : quads)
    for (long v : q) id[v] = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (id[j * n + i] == 0) {
        id[j * n + i] = static_cast<long>(bind.size()) + 1;  // OBJ's 1-based index
        bind.push_back(
            bind_point(static_cast<double>(i) / (n - 1), static_cast<double>(j) / (n - 1)));
      }
  std::string faces;
  for (const auto& q : quads) {
    faces += "f";
    for (long v : q) faces.append(" ").append(std::to_string(id[v]));
    faces += "\n";
  }
  auto mesh_text = [&](double angle) {
    std::string out =
        "# skinslide benchmark case: " + std::to_string(bind.size()) + " vertices\no surface\n";
    out.reserve(bind.size() * 32 + faces.size());
    for (const P3& b : bind) {
      const P3 p = angle == 0 ? b : bend(b, angle);
      out += "v ";
      append_fixed(out, p.x);
      out += ' ';
      append_fixed(out, p.y);
      out += ' ';
      append_fixed(out, p.z);
      out += '\n';
    }
    return out + faces;
  };
  write(dir / "bind.obj", mesh_text(0));
  std::string patch = "# every face but the outer ring\n";
  for (size_t f = 0; f < quads.size();) {  // runs of consecutive faces as ranges
    if (border[f]) {
      ++f;
      continue;
    }
    size_t last = f;
    while (last + 1 < quads.size() && !border[last + 1]) ++last;
    patch.append(std::to_string(f)).append("-").append(std::to_string(last)).append("\n");
    f = last + 1;
  }
  write(dir / "patch.txt", patch);
  for (int k = 1; k <= frames; ++k) {
    // Bends from 20 to 80 degrees and back, so consecutive frames differ.
    const double deg = 20 + 60 * std::fabs(std::sin(kPi * k / 8.0));
    char name[32];
    std::snprintf(name, sizeof name, "f.%04d.obj", k);
    write(dir / "frames" / name, mesh_text(deg * kPi / 180));
  }
  std::printf("%zu vertices, %zu faces, %d frames\n", bind.size(), quads.size(), frames);
  return 0;
}
