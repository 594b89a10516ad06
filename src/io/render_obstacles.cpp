// Obstacles in particle pictures: a per-pixel test of the signed distance in
// 2D, sphere tracing along the orthographic view rays in 3D.
#include "io/render_obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/obstacle.hpp"

namespace sablier {
namespace {

template <int D>
std::vector<Obstacle<D>> obstacles_at(const std::vector<ObstacleConfig>& configs, double time) {
  std::vector<Obstacle<D>> out;
  for (const ObstacleConfig& c : configs) out.push_back(at_time(make_obstacle<D>(c), time));
  return out;
}

// Pixels [x0, x1) x [y0, y1) that may show the box: its projection's
// bounding rectangle, clipped to the canvas.
struct PixelRect {
  int x0, y0, x1, y1;
};

PixelRect box_pixels(const Canvas& canvas, const Camera& cam) {
  const Camera::Rect& r = cam.content();
  return {std::max(0, static_cast<int>(std::floor(r.x0))),
          std::max(0, static_cast<int>(std::floor(r.y0))),
          std::min(canvas.width(), static_cast<int>(std::ceil(r.x1)) + 1),
          std::min(canvas.height(), static_cast<int>(std::ceil(r.y1)) + 1)};
}

bool in_box(const Box& box, const double* p) {
  for (int a = 0; a < box.dimension; ++a)
    if (p[a] < box.lo[a] || p[a] > box.hi[a]) return false;
  return true;
}

// The stretch [t0, t1] of the ray o + t f inside the box (slab test) and
// the axis of the face it enters by; false if the ray misses the box.
bool clip_ray(const Box& box, const Vec<3>& o, const Vec<3>& f, double* t0, double* t1, int* axis) {
  *t0 = -std::numeric_limits<double>::infinity(), *t1 = -*t0, *axis = 0;
  for (int a = 0; a < 3; ++a) {
    if (f[a] == 0.0) {
      if (o[a] < box.lo[a] || o[a] > box.hi[a]) return false;
      continue;
    }
    const double ta = (box.lo[a] - o[a]) / f[a], tb = (box.hi[a] - o[a]) / f[a];
    if (std::min(ta, tb) > *t0) *t0 = std::min(ta, tb), *axis = a;
    *t1 = std::min(*t1, std::max(ta, tb));
  }
  return *t0 <= *t1;
}

struct Hit {
  double depth = 0.0;  // m along the view ray
  Vec<3> normal = Vec<3>::Zero();
  int which = -1;  // the obstacle's index
};

// Sphere tracing (Hart 1996): the signed distance of the union (a lower
// bound of the distance to it: exact for planes, balls and boxes, a bound
// for cylinders) is a step that cannot cross a surface. Steps are at least
// `min_step` (half a pixel: grazing rays would crawl otherwise), so a step
// that lands inside is bisected back to the surface. A ray that starts
// inside a solid where it enters the box hits the solid's cut face.
bool trace(const std::vector<Obstacle<3>>& obstacles, const Box& box, const Vec<3>& o,
           const Vec<3>& f, double pixel, Hit* hit) {
  constexpr int kMaxSteps = 512;
  double t0, t1;
  int axis;
  if (!clip_ray(box, o, f, &t0, &t1, &axis)) return false;
  const double tolerance = 0.1 * pixel, min_step = 0.5 * pixel;
  double outside = t0, t = t0;
  for (int step = 0; step < kMaxSteps && t <= t1; ++step) {
    double s = obstacle_distance(obstacles, Vec<3>(o + t * f), &hit->normal, &hit->which);
    if (s < 0.0 && step == 0) {  // the cut face
      hit->normal = Vec<3>::Zero();
      hit->normal[axis] = f[axis] > 0.0 ? -1.0 : 1.0;
      hit->depth = t;
      return true;
    }
    if (s < 0.0) {
      double inside = t;
      for (int k = 0; k < 12; ++k) {
        const double mid = 0.5 * (outside + inside);
        const double sm = obstacle_distance(obstacles, Vec<3>(o + mid * f), &hit->normal);
        (sm < 0.0 ? inside : outside) = mid;
      }
      t = outside;
      s = obstacle_distance(obstacles, Vec<3>(o + t * f), &hit->normal, &hit->which);
    }
    if (s < tolerance) {
      hit->depth = t;
      return true;
    }
    outside = t;
    t += std::max(s, min_step);
  }
  return false;
}

// Outlines where a solid ends: an obstacle pixel with, within `edge_px`
// along a row or a column, a pixel showing no obstacle, or another one
// farther away.
void draw_silhouettes(Canvas& canvas, const PixelRect& r, const std::vector<int>& which,
                      const std::vector<float>& depth, int edge_px) {
  const int w = canvas.width();
  const auto index = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
  const auto ends_at = [&](std::size_t p, int x, int y) {
    if (x < r.x0 || y < r.y0 || x >= r.x1 || y >= r.y1) return false;
    const std::size_t q = index(x, y);
    return which[q] != which[p] && (which[q] < 0 || depth[q] > depth[p]);
  };
  for (int y = r.y0; y < r.y1; ++y) {
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t p = index(x, y);
      if (which[p] < 0) continue;
      bool edge = false;
      for (int k = 1; k <= edge_px && !edge; ++k)
        edge = ends_at(p, x - k, y) || ends_at(p, x + k, y) || ends_at(p, x, y - k) ||
               ends_at(p, x, y + k);
      if (edge) canvas.set(x, y, kObstacleEdge);
    }
  }
}

}  // namespace

double lambert(const double n[3]) {
  // Unit vector in (right, up, towards viewer) coordinates.
  static const double kNorm = std::sqrt(0.4 * 0.4 + 0.7 * 0.7 + 0.6 * 0.6);
  static const double kLight[3] = {-0.4 / kNorm, 0.7 / kNorm, 0.6 / kNorm};
  return std::max(0.0, n[0] * kLight[0] + n[1] * kLight[1] + n[2] * kLight[2]);
}

void fill_obstacles_2d(Canvas& canvas, const std::vector<ObstacleConfig>& configs, double time,
                       const Box& box, const Camera& cam, int edge_px) {
  if (configs.empty()) return;
  const std::vector<Obstacle<2>> obstacles = obstacles_at<2>(configs, time);
  const double edge = edge_px / cam.pixels_per_metre();
  const PixelRect r = box_pixels(canvas, cam);
  for (int y = r.y0; y < r.y1; ++y) {
    for (int x = r.x0; x < r.x1; ++x) {
      double p[2];
      cam.unproject(x + 0.5, y + 0.5, 0.0, p);
      if (!in_box(box, p)) continue;
      Vec<2> normal;
      const double s = obstacle_distance(obstacles, Vec<2>(p[0], p[1]), &normal);
      if (s < 0.0) canvas.set(x, y, s > -edge ? kObstacleEdge : kObstacle);
    }
  }
}

void draw_obstacles_3d(Canvas& canvas, std::vector<float>& zbuf,
                       const std::vector<ObstacleConfig>& configs, double time, const Box& box,
                       const Camera& cam, int edge_px) {
  if (configs.empty()) return;
  const std::vector<Obstacle<3>> obstacles = obstacles_at<3>(configs, time);
  const double pixel = 1.0 / cam.pixels_per_metre();
  const PixelRect r = box_pixels(canvas, cam);
  const std::size_t n = static_cast<std::size_t>(canvas.width()) * canvas.height();
  std::vector<int> which(n, -1);
  std::vector<float> depth(n, std::numeric_limits<float>::infinity());
  for (int y = r.y0; y < r.y1; ++y) {
    for (int x = r.x0; x < r.x1; ++x) {
      Vec<3> o, far;
      cam.unproject(x + 0.5, y + 0.5, 0.0, o.data());
      cam.unproject(x + 0.5, y + 0.5, 1.0, far.data());
      Hit hit;
      if (!trace(obstacles, box, o, Vec<3>(far - o), pixel, &hit)) continue;
      const std::size_t p = static_cast<std::size_t>(y) * canvas.width() + x;
      const float d = static_cast<float>(hit.depth);
      if (d >= zbuf[p]) continue;
      zbuf[p] = depth[p] = d;
      which[p] = hit.which;
      double screen[3];
      cam.to_screen(hit.normal.data(), screen);
      canvas.set(x, y, shade(kObstacle, 0.45 + 0.55 * lambert(screen)));
    }
  }
  draw_silhouettes(canvas, r, which, depth, edge_px);
}

}  // namespace sablier
