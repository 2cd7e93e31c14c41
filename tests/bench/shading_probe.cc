// Can the object's shading pin its rotation? A feasibility probe for a photometric term
// (issue 12: the rotation about the rig's vertical axis, which a horizontal ring of cameras
// sees only through the silhouettes' shape, spreads by 0.1–0.17° on the Cycles scenes).
//
// At the ground truth of every --step-th frame of SEQ: the inside pixels of each view (mask
// eroded by --erode px, every --stride px) with the mesh's smooth normal n (rig frame, vertex
// normals interpolated as Cycles shades a smooth mesh) and the linear RGB I (sRGB decoded).
// Fits a distant light shared by all frames and views, I_c = Σ_k L_ck Y_k(n) with the real
// spherical harmonics up to order 2 (iteratively reweighted, Huber at 2 robust sd: highlights,
// shadows and reflections are outliers of this model). Prints the fit's residual. Then per
// frame the Huber energy of the same pixels (kept fixed) under the fitted light with the object
// turned about its bounding-box centre by δ about each rig axis, δ in ±--range° on a grid:
// the minimising δ (a parabola through the grid's lowest three) per axis, its mean and spread
// over the frames, and the energy's curvature, i.e. how sharply the shading locates the turn
// and whether its minimum lies at the truth.
//
//   build/tests/bench/shading_probe --sequence SEQ [--step 4] [--erode 4] [--stride 2]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bcot/core/image_io.h"
#include "bcot/core/linear_rgb.h"
#include "bcot/render/ray_caster.h"
#include "ground_truth_sequence.h"

namespace bcot {
namespace {

using Basis = Eigen::Matrix<double, 9, 1>;

Basis ShBasis(const Eigen::Vector3d& n) {
  Basis y;
  y << 1.0, n.x(), n.y(), n.z(), n.x() * n.y(), n.x() * n.z(), n.y() * n.z(),
      n.x() * n.x() - n.y() * n.y(), 3.0 * n.z() * n.z() - 1.0;
  return y;
}

// The smooth normal (object frame) at `p` on triangle `t`.
Eigen::Vector3d SmoothNormal(const Mesh& mesh, const std::vector<Eigen::Vector3f>& normals, int t,
                             const Eigen::Vector3d& p) {
  const Eigen::Vector3i& tri = mesh.triangles()[t];
  const Eigen::Vector3d a = mesh.vertices()[tri[0]].cast<double>();
  const Eigen::Vector3d b = mesh.vertices()[tri[1]].cast<double>();
  const Eigen::Vector3d c = mesh.vertices()[tri[2]].cast<double>();
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  const double wa = (c - b).cross(p - b).dot(n) / area2;
  const double wb = (a - c).cross(p - c).dot(n) / area2;
  const double wc = 1.0 - wa - wb;
  return (wa * normals[tri[0]].cast<double>() + wb * normals[tri[1]].cast<double>() +
          wc * normals[tri[2]].cast<double>())
      .normalized();
}

struct Sample {
  int frame = 0;
  int view = 0;
  Eigen::Vector2i pixel;
  Eigen::Vector3d rgb;
  Eigen::Vector3d normal_in_rig;
};

double Huber(double r, double k) {
  const double a = std::abs(r);
  return a <= k ? 0.5 * r * r : k * (a - 0.5 * k);
}

int Run(int argc, char** argv) {
  CLI::App app{"Shading as a rotation cue: SH light fit and energy vs turn (issue 12)"};
  std::string sequence_dir;
  int step = 4, erode = 4, stride = 2;
  double range_deg = 0.6;
  app.add_option("--sequence", sequence_dir)->required();
  app.add_option("--step", step, "every step-th frame");
  app.add_option("--erode", erode, "px taken off the mask's edge");
  app.add_option("--stride", stride, "pixel stride");
  app.add_option("--range", range_deg, "turns δ within ±range (deg)");
  CLI11_PARSE(app, argc, argv);

  const StatusOr<bench::GroundTruthSequence> loaded = bench::LoadGroundTruthSequence(sequence_dir);
  if (!loaded.ok()) {
    std::fprintf(stderr, "%s\n", loaded.status().message().c_str());
    return 2;
  }
  const Sequence& sequence = loaded->sequence;
  const Mesh& mesh = loaded->mesh;
  const RayCaster caster(mesh);
  const std::vector<Eigen::Vector3f> vertex_normals = mesh.VertexNormals();
  const LinearTable table{ImageResponse()};
  const int views = sequence.rig.size();
  RenderOptions render;
  render.margin_px = 4;
  render.depth = false;
  render.normal_in_cam = false;

  // Renders `view` at rig_from_object and returns, per requested pixel, the rig-frame smooth
  // normal (NaN where missed).
  auto normals_at = [&](int view, const Eigen::Isometry3d& rig_from_object,
                        const std::vector<Eigen::Vector2i>& pixels) {
    const RigCamera& camera = sequence.rig[view];
    const Eigen::Isometry3d cam_from_object = camera.cam_from_rig * rig_from_object;
    const RenderedView rendered = caster.Render(camera.camera, cam_from_object, render);
    std::vector<Eigen::Vector3d> out;
    for (const Eigen::Vector2i& p : pixels) {
      const int x = p.x() - rendered.roi.x, y = p.y() - rendered.roi.y;
      if (x < 0 || y < 0 || x >= rendered.roi.width || y >= rendered.roi.height ||
          rendered.triangle_id(y, x) < 0) {
        out.push_back(Eigen::Vector3d::Constant(std::nan("")));
        continue;
      }
      const cv::Vec3f q = rendered.point_in_object(y, x);
      out.push_back(rig_from_object.linear() * SmoothNormal(mesh, vertex_normals,
                                                            rendered.triangle_id(y, x),
                                                            Eigen::Vector3d(q[0], q[1], q[2])));
    }
    return out;
  };

  // Samples at the truth.
  std::vector<Sample> samples;
  std::vector<int> frames;
  for (int f = 0; f < sequence.num_frames; f += step) frames.push_back(f);
  for (int f : frames) {
    for (int v = 0; v < views; ++v) {
      const StatusOr<cv::Mat3b> image =
          ReadCameraImage(sequence.image_paths[v][f], sequence.rig[v].camera);
      if (!image.ok()) {
        std::fprintf(stderr, "%s\n", image.status().message().c_str());
        return 2;
      }
      const Eigen::Isometry3d cam_from_object = sequence.rig[v].cam_from_rig * loaded->truth[f];
      const RenderedView rendered = caster.Render(sequence.rig[v].camera, cam_from_object, render);
      cv::Mat1b inner;
      cv::erode(
          rendered.mask, inner,
          cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * erode + 1, 2 * erode + 1)));
      std::vector<Eigen::Vector2i> pixels;
      for (int y = 0; y < inner.rows; ++y) {
        for (int x = 0; x < inner.cols; ++x) {
          const int u = x + rendered.roi.x, w = y + rendered.roi.y;
          if (inner(y, x) == 0 || u % stride != 0 || w % stride != 0) continue;
          pixels.emplace_back(u, w);
        }
      }
      const std::vector<Eigen::Vector3d> normals = normals_at(v, loaded->truth[f], pixels);
      for (size_t i = 0; i < pixels.size(); ++i) {
        if (!normals[i].allFinite()) continue;
        const cv::Vec3b& code = (*image)(pixels[i].y(), pixels[i].x());
        Sample s;
        s.frame = f;
        s.view = v;
        s.pixel = pixels[i];
        s.rgb = Eigen::Vector3d(table[code[2]], table[code[1]], table[code[0]]);
        s.normal_in_rig = normals[i];
        samples.push_back(s);
      }
    }
  }
  if (samples.size() < 100) {
    std::fprintf(stderr, "too few inside pixels (%zu)\n", samples.size());
    return 2;
  }

  // The light: IRLS with Huber weights at 2 robust sd per channel.
  Eigen::Matrix<double, 9, 3> light = Eigen::Matrix<double, 9, 3>::Zero();
  std::array<double, 3> scale{1.0, 1.0, 1.0};
  for (int iteration = 0; iteration < 8; ++iteration) {
    for (int c = 0; c < 3; ++c) {
      Eigen::Matrix<double, 9, 9> ata = Eigen::Matrix<double, 9, 9>::Zero();
      Eigen::Matrix<double, 9, 1> atb = Eigen::Matrix<double, 9, 1>::Zero();
      for (const Sample& s : samples) {
        const Basis y = ShBasis(s.normal_in_rig);
        const double r = y.dot(light.col(c)) - s.rgb[c];
        const double k = 2.0 * scale[c];
        const double w = iteration == 0 || std::abs(r) <= k ? 1.0 : k / std::abs(r);
        ata += w * y * y.transpose();
        atb += w * y * s.rgb[c];
      }
      light.col(c) = ata.ldlt().solve(atb);
      std::vector<double> residuals;
      for (const Sample& s : samples) {
        residuals.push_back(std::abs(ShBasis(s.normal_in_rig).dot(light.col(c)) - s.rgb[c]));
      }
      std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2,
                       residuals.end());
      scale[c] = std::max(1e-4, 1.4826 * residuals[residuals.size() / 2]);
    }
  }
  Eigen::Vector3d mean_rgb = Eigen::Vector3d::Zero();
  for (const Sample& s : samples) mean_rgb += s.rgb;
  mean_rgb /= samples.size();
  std::printf("%zu inside pixels over %zu frames x %d views; mean linear RGB %.3f %.3f %.3f\n",
              samples.size(), frames.size(), views, mean_rgb.x(), mean_rgb.y(), mean_rgb.z());
  std::printf("SH-2 light fit: robust residual sd per channel %.4f %.4f %.4f\n", scale[0], scale[1],
              scale[2]);

  // Energy vs turn per frame and rig axis, both views together, pixels fixed.
  const Eigen::Vector3d centre = mesh.bbox_center();
  const int grid = 13;
  std::array<std::vector<double>, 3> minima;
  std::array<std::vector<double>, 3> curvatures;
  for (int f : frames) {
    std::vector<std::vector<Eigen::Vector2i>> pixels(views);
    std::vector<std::vector<const Sample*>> of_view(views);
    for (const Sample& s : samples) {
      if (s.frame != f) continue;
      pixels[s.view].push_back(s.pixel);
      of_view[s.view].push_back(&s);
    }
    std::printf("frame %3d", f);
    const Eigen::Vector3d c_rig = loaded->truth[f] * centre;
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<double> deltas, energies;
      for (int g = 0; g < grid; ++g) {
        const double delta = -range_deg + 2.0 * range_deg * g / (grid - 1);
        const Eigen::Isometry3d turn =
            Eigen::Translation3d(c_rig) *
            Eigen::AngleAxisd(delta * M_PI / 180.0, Eigen::Vector3d::Unit(axis)) *
            Eigen::Translation3d(-c_rig);
        const Eigen::Isometry3d pose = turn * loaded->truth[f];
        double energy = 0.0;
        for (int v = 0; v < views; ++v) {
          const std::vector<Eigen::Vector3d> normals = normals_at(v, pose, pixels[v]);
          for (size_t i = 0; i < normals.size(); ++i) {
            if (!normals[i].allFinite()) continue;
            const Basis y = ShBasis(normals[i]);
            for (int c = 0; c < 3; ++c) {
              energy += Huber((y.dot(light.col(c)) - of_view[v][i]->rgb[c]) / scale[c], 2.0);
            }
          }
        }
        deltas.push_back(delta);
        energies.push_back(energy);
      }
      const int best =
          static_cast<int>(std::min_element(energies.begin(), energies.end()) - energies.begin());
      const int mid = std::clamp(best, 1, grid - 2);
      const double h = deltas[1] - deltas[0];
      const double e0 = energies[mid - 1], e1 = energies[mid], e2 = energies[mid + 1];
      const double curvature = (e0 - 2.0 * e1 + e2) / (h * h);
      const double minimum =
          curvature > 0.0 ? deltas[mid] + 0.5 * h * (e0 - e2) / (e0 - 2.0 * e1 + e2) : deltas[best];
      minima[axis].push_back(minimum);
      curvatures[axis].push_back(curvature);
      std::printf(" | %c min %+.3f° curv %.3g", "xyz"[axis], minimum, curvature);
    }
    std::printf("\n");
  }
  for (int axis = 0; axis < 3; ++axis) {
    double mean = 0.0, sq = 0.0, curv = 0.0;
    for (size_t i = 0; i < minima[axis].size(); ++i) {
      mean += minima[axis][i];
      sq += minima[axis][i] * minima[axis][i];
      curv += curvatures[axis][i];
    }
    const double n = static_cast<double>(minima[axis].size());
    mean /= n;
    std::printf(
        "rig axis %c: minimum at %+.3f° ± %.3f° (mean ± sd over %zu frames), mean curvature %.3g "
        "per deg²\n",
        "xyz"[axis], mean, std::sqrt(std::max(0.0, sq / n - mean * mean)), minima[axis].size(),
        curv / n);
  }
  return 0;
}

}  // namespace
}  // namespace bcot

int main(int argc, char** argv) { return bcot::Run(argc, argv); }
