// Scanline-free triangle rasterization with edge functions and a depth buffer (Pineda 1988, "A parallel algorithm for
// polygon rasterization"), perspective projection, and flat two-sided Lambert shading with an ambient term.
#include "clothcd/render/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace clothcd::render {
namespace {

struct View {
  Eigen::Vector3d right, up, forward, eye;
  double focal;  // pixels
  double cx, cy;
};

View make_view(const Camera& camera, const RenderSettings& settings) {
  View v;
  v.eye = camera.eye;
  v.forward = (camera.target - camera.eye).normalized();
  v.right = v.forward.cross(camera.up).normalized();
  v.up = v.right.cross(v.forward);
  v.focal = 0.5 * settings.height / std::tan(0.5 * camera.fov_degrees * M_PI / 180.0);
  v.cx = 0.5 * settings.width;
  v.cy = 0.5 * settings.height;
  return v;
}

unsigned char to_byte(double c) { return static_cast<unsigned char>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); }

}  // namespace

Image render(const std::vector<RenderItem>& items, const Camera& camera, const RenderSettings& settings) {
  if (settings.width <= 0 || settings.height <= 0) throw std::invalid_argument("render: image size must be positive");
  const Eigen::Vector3d& bg = settings.background;
  Image image(settings.width, settings.height, to_byte(bg.x()), to_byte(bg.y()), to_byte(bg.z()));
  std::vector<double> depth(static_cast<size_t>(settings.width) * settings.height, std::numeric_limits<double>::infinity());
  const View view = make_view(camera, settings);
  const Eigen::Vector3d light = settings.light_direction.normalized();
  constexpr double kNear = 1e-3;

  for (const RenderItem& item : items) {
    if (item.mesh == nullptr) throw std::invalid_argument("render: null mesh");
    const TriangleMesh& mesh = *item.mesh;
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
      Eigen::Vector3d p[3];
      Eigen::Vector3d s[3];  // screen x, y and camera depth
      bool visible = true;
      for (int k = 0; k < 3; ++k) {
        p[k] = mesh.vertices.row(mesh.faces(f, k)).transpose();
        const Eigen::Vector3d d = p[k] - view.eye;
        const double z = d.dot(view.forward);
        if (z < kNear) visible = false;
        s[k] = {view.cx + view.focal * d.dot(view.right) / z, view.cy - view.focal * d.dot(view.up) / z, z};
      }
      if (!visible) continue;
      const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
      if (normal.squaredNorm() == 0) continue;
      const double lambert = std::abs(normal.normalized().dot(light));  // two-sided: cloth has no inside
      const Eigen::Vector3d shade = item.color * (0.35 + 0.65 * lambert);
      const unsigned char r = to_byte(shade.x()), g = to_byte(shade.y()), b = to_byte(shade.z());

      const double area = (s[1].x() - s[0].x()) * (s[2].y() - s[0].y()) - (s[1].y() - s[0].y()) * (s[2].x() - s[0].x());
      if (area == 0) continue;
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x(), s[1].x(), s[2].x()}))));
      const int x1 = std::min(settings.width - 1, static_cast<int>(std::ceil(std::max({s[0].x(), s[1].x(), s[2].x()}))));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y(), s[1].y(), s[2].y()}))));
      const int y1 = std::min(settings.height - 1, static_cast<int>(std::ceil(std::max({s[0].y(), s[1].y(), s[2].y()}))));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const double px = x + 0.5, py = y + 0.5;
          double w[3];
          for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d& a = s[(k + 1) % 3];
            const Eigen::Vector3d& c = s[(k + 2) % 3];
            w[k] = ((c.x() - a.x()) * (py - a.y()) - (c.y() - a.y()) * (px - a.x())) / area;
          }
          if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
          // Perspective-correct depth: interpolate 1/z in screen space.
          const double inverse_z = w[0] / s[0].z() + w[1] / s[1].z() + w[2] / s[2].z();
          const double z = 1.0 / inverse_z;
          const size_t pixel = static_cast<size_t>(y) * settings.width + x;
          if (z >= depth[pixel]) continue;
          depth[pixel] = z;
          image.rgb[3 * pixel] = r;
          image.rgb[3 * pixel + 1] = g;
          image.rgb[3 * pixel + 2] = b;
        }
      }
    }
  }
  return image;
}

Camera frame_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Camera camera;
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-6);
  const Eigen::Vector3d direction = Eigen::Vector3d(0.55, 0.6, 1.0).normalized();
  const double distance = radius / std::sin(0.5 * camera.fov_degrees * M_PI / 180.0) * 1.05;
  camera.target = centre;
  camera.eye = centre + distance * direction;
  return camera;
}

}  // namespace clothcd::render
