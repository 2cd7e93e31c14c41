// The BOP export checked against the format's definition (bop_toolkit's
// docs/bop_datasets_format.md), not against the exporter's own code: the model is re-projected
// from the JSON files and the PLY alone (read here with nlohmann-json and a PLY reader of this
// file, rasterised with cv::fillConvexPoly) and compared with mask_visib; every JSON file's field
// names, types and shapes are checked.
#include "bcot/export/bop_writer.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/export/exporter.h"
#include "bcot/render/mesh.h"
#include "bcot/synth/synthesizer.h"
#include "export/coverage_frames.h"
#include "synth_scenes.h"
#include "test_util.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using ::testing::HasSubstr;

constexpr int kFrames = 4;

// A binocular synthetic sequence (cam0, cam1; 4 frames, 320×256), optionally with strong barrel
// distortion. The frames are replaced by the object's exact coverage (0..255), so an exported
// image shows where the object is in the exported camera.
void SynthesizeSequence(const std::string& out, bool distorted) {
  SynthOptions options = test::SmallBinocularSynthOptions(320, 256, kFrames);
  options.seed = 5;
  options.cameras.hfov_deg = 70.0;
  options.cameras.distance_mm = 400.0;
  options.object.size_mm = 220.0;
  if (distorted) options.cameras.distortion = {-0.3, 0.1, 0.001, -0.001, 0.0};
  options.background.clutter_shapes = 0;
  options.render.object_samples_per_axis = 4;
  options.output.write_coverage = true;
  ASSERT_TRUE(Synthesize(options, out).ok());
  test::ReplaceFramesWithCoverage(out, kFrames);
}

Json ReadJson(const std::string& path) {
  const StatusOr<std::string> text = ReadTextFile(path);
  EXPECT_TRUE(text.ok()) << path;
  const Json json = Json::parse(text.ok() ? *text : "", nullptr, /*allow_exceptions=*/false);
  EXPECT_FALSE(json.is_discarded()) << path;
  return json;
}

// An ASCII PLY as BOP defines its models: vertices (x, y, z first) and triangle faces.
struct PlyModel {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;
};
PlyModel ReadAsciiPly(const std::string& path) {
  PlyModel model;
  std::ifstream in(path);
  std::string line;
  int vertex_count = -1, face_count = -1, vertex_properties = 0;
  std::getline(in, line);
  EXPECT_EQ(line, "ply");
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word, element;
    words >> word;
    if (word == "format") {
      words >> word;
      EXPECT_EQ(word, "ascii");
    } else if (word == "element") {
      words >> element;
      (element == "vertex" ? vertex_count : face_count) = 0;
      words >> (element == "vertex" ? vertex_count : face_count);
    } else if (word == "property" && face_count < 0) {
      ++vertex_properties;
    }
  }
  EXPECT_GE(vertex_properties, 3);
  for (int i = 0; i < vertex_count; ++i) {
    std::getline(in, line);
    std::istringstream values(line);
    Eigen::Vector3d v;
    values >> v.x() >> v.y() >> v.z();
    model.vertices.push_back(v);
  }
  for (int i = 0; i < face_count; ++i) {
    int n = 0;
    std::array<int, 3> face{};
    in >> n >> face[0] >> face[1] >> face[2];
    EXPECT_EQ(n, 3);
    model.faces.push_back(face);
  }
  EXPECT_TRUE(in.good() || in.eof()) << path;
  return model;
}

Eigen::Matrix3d Matrix3(const Json& values) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = values.at(i).get<double>();
  return m;
}
Eigen::Vector3d Vector3(const Json& values) {
  return {values.at(0).get<double>(), values.at(1).get<double>(), values.at(2).get<double>()};
}

// The model's silhouette at K, R, t, rasterised with 8×8 sub-pixels per pixel (pixel centres at
// integers) and kept where at least half a pixel is covered.
cv::Mat1b RasteriseModel(const PlyModel& model, const Eigen::Matrix3d& K, const Eigen::Matrix3d& R,
                         const Eigen::Vector3d& t, cv::Size size) {
  constexpr int kSub = 8, kShift = 8;
  cv::Mat1b fine = cv::Mat1b::zeros(size.height * kSub, size.width * kSub);
  std::vector<cv::Point> projected(model.vertices.size());
  std::vector<bool> in_front(model.vertices.size());
  for (size_t i = 0; i < model.vertices.size(); ++i) {
    const Eigen::Vector3d p = K * (R * model.vertices[i] + t);
    in_front[i] = p.z() > 1e-6;
    const double u = kSub * (p.x() / p.z() + 0.5) - 0.5, v = kSub * (p.y() / p.z() + 0.5) - 0.5;
    projected[i] = cv::Point(static_cast<int>(std::lround(u * (1 << kShift))),
                             static_cast<int>(std::lround(v * (1 << kShift))));
  }
  for (const std::array<int, 3>& face : model.faces) {
    if (!in_front[face[0]] || !in_front[face[1]] || !in_front[face[2]]) continue;
    const cv::Point triangle[3] = {projected[face[0]], projected[face[1]], projected[face[2]]};
    cv::fillConvexPoly(fine, triangle, 3, cv::Scalar(255), cv::LINE_8, kShift);
  }
  cv::Mat coarse;
  cv::resize(fine, coarse, size, 0, 0, cv::INTER_AREA);
  return coarse >= 128;
}

double IoU(const cv::Mat1b& a, const cv::Mat1b& b) {
  const double intersection = cv::countNonZero(a & b), both = cv::countNonZero(a | b);
  return both > 0 ? intersection / both : 1.0;
}

void ExpectNumbers(const Json& value, size_t count, const std::string& where) {
  ASSERT_TRUE(value.is_array()) << where;
  ASSERT_EQ(value.size(), count) << where;
  for (const Json& number : value) EXPECT_TRUE(number.is_number()) << where;
}
void ExpectIntegers(const Json& value, size_t count, const std::string& where) {
  ExpectNumbers(value, count, where);
  for (const Json& number : value) EXPECT_TRUE(number.is_number_integer()) << where;
}
// Keys "0", "1", … (image ids), one per exported image.
void ExpectImageIds(const Json& json, int count, const std::string& where) {
  ASSERT_TRUE(json.is_object()) << where;
  ASSERT_EQ(json.size(), static_cast<size_t>(count)) << where;
  for (int i = 0; i < count; ++i) EXPECT_TRUE(json.contains(std::to_string(i))) << where << i;
}
std::vector<std::string> Keys(const Json& object) {
  std::vector<std::string> keys;
  for (auto it = object.begin(); it != object.end(); ++it) keys.push_back(it.key());
  std::sort(keys.begin(), keys.end());
  return keys;
}

class BopWriterTest : public ::testing::TestWithParam<bool> {
 protected:
  void SetUp() override { SynthesizeSequence(dir_.File("seq"), Distorted()); }
  bool Distorted() const { return GetParam(); }
  std::string Sequence() const { return dir_.File("seq"); }
  std::string Annotation() const { return dir_.File("seq/gt"); }

  test::TempDir dir_;
};

TEST_P(BopWriterTest, ModelReprojectedFromTheJsonAloneMatchesMaskVisib) {
  test::TempDir out;
  ExportOptions options;
  options.format = ExportFormat::kBop;
  options.bop.obj_id = 7;
  const StatusOr<ExportSummary> summary =
      ExportAnnotation(Sequence(), Annotation(), out.path(), options);
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->undistorted, Distorted());
  EXPECT_EQ(summary->cameras, (std::vector<std::string>{"cam0", "cam1"}));

  const PlyModel model = ReadAsciiPly(out.File("models/obj_000007.ply"));
  ASSERT_GT(model.faces.size(), 100u);
  // BOP's model frame: origin at the bounding-box centre, and models_info agrees with the PLY.
  Eigen::Vector3d min = model.vertices[0], max = model.vertices[0];
  for (const Eigen::Vector3d& v : model.vertices) {
    min = min.cwiseMin(v);
    max = max.cwiseMax(v);
  }
  EXPECT_LT((0.5 * (min + max)).norm(), 1e-3);
  const Json info = ReadJson(out.File("models/models_info.json")).at("7");
  EXPECT_NEAR(info.at("min_x").get<double>(), min.x(), 1e-3);
  EXPECT_NEAR(info.at("size_z").get<double>(), max.z() - min.z(), 1e-3);
  EXPECT_LE(info.at("diameter").get<double>(), (max - min).norm() + 1e-3);
  EXPECT_GE(info.at("diameter").get<double>(), (max - min).maxCoeff() - 1e-3);
  EXPECT_FALSE(info.contains("symmetries_continuous"));  // the knot has none

  Eigen::Matrix3d R_w2c[2];
  Eigen::Vector3d t_w2c[2];
  Eigen::Matrix3d R_m2c[2];
  Eigen::Vector3d t_m2c[2];
  for (int view = 0; view < 2; ++view) {
    const std::string scene = out.File("test/000000");
    const std::string cam = fmt::format("_cam{}", view);
    const Json cameras = ReadJson(fmt::format("{}/scene_camera{}.json", scene, cam));
    const Json gts = ReadJson(fmt::format("{}/scene_gt{}.json", scene, cam));
    const Json infos = ReadJson(fmt::format("{}/scene_gt_info{}.json", scene, cam));
    for (int image = 0; image < kFrames; ++image) {
      const std::string id = std::to_string(image);
      const Json& camera = cameras.at(id);
      const Json& gt = gts.at(id).at(0);
      EXPECT_EQ(gt.at("obj_id").get<int>(), 7);
      const Eigen::Matrix3d K = Matrix3(camera.at("cam_K"));
      const Eigen::Matrix3d R = Matrix3(gt.at("cam_R_m2c"));
      const Eigen::Vector3d t = Vector3(gt.at("cam_t_m2c"));
      const cv::Mat1b mask_visib =
          cv::imread(fmt::format("{}/mask_visib{}/{:06d}_000000.png", scene, cam, image),
                     cv::IMREAD_GRAYSCALE);
      ASSERT_EQ(mask_visib.size(), cv::Size(320, 256));
      const cv::Mat1b projected = RasteriseModel(model, K, R, t, mask_visib.size());
      const double iou = IoU(projected, mask_visib > 0);
      EXPECT_GE(iou, 0.98) << "view " << view << " image " << image;
      // The criterion has teeth: the object 3 % further away fails it.
      EXPECT_LT(IoU(RasteriseModel(model, K, R, 1.03 * t, mask_visib.size()), mask_visib > 0),
                0.98);
      // The exported image shows the object there (undistorted to the pinhole cam_K).
      const cv::Mat rgb =
          cv::imread(fmt::format("{}/rgb{}/{:06d}.png", scene, cam, image), cv::IMREAD_GRAYSCALE);
      ASSERT_EQ(rgb.size(), cv::Size(320, 256));
      EXPECT_GE(IoU(projected, rgb >= 128), 0.95) << "view " << view << " image " << image;
      const Json& gt_info = infos.at(id).at(0);
      EXPECT_EQ(gt_info.at("px_count_visib").get<int>(), cv::countNonZero(mask_visib));
      const cv::Rect box = cv::boundingRect(mask_visib);
      EXPECT_EQ(gt_info.at("bbox_visib").at(0).get<int>(), box.x);
      EXPECT_EQ(gt_info.at("bbox_visib").at(1).get<int>(), box.y);
      std::printf("view %d image %d: IoU(PLY re-projected, mask_visib) = %.4f\n", view, image, iou);
      if (image == 0) {
        R_w2c[view] = Matrix3(camera.at("cam_R_w2c"));
        t_w2c[view] = Vector3(camera.at("cam_t_w2c"));
        R_m2c[view] = R;
        t_m2c[view] = t;
      }
    }
  }
  // World = the rig: both views' m2c agree on one world_from_model.
  const Eigen::Matrix3d R_w2m0 = R_w2c[0].transpose() * R_m2c[0];
  const Eigen::Matrix3d R_w2m1 = R_w2c[1].transpose() * R_m2c[1];
  EXPECT_TRUE(R_w2m0.isApprox(R_w2m1, 1e-9));
  EXPECT_TRUE((R_w2c[0].transpose() * (t_m2c[0] - t_w2c[0]))
                  .isApprox(R_w2c[1].transpose() * (t_m2c[1] - t_w2c[1]), 1e-9));
}

TEST_P(BopWriterTest, EveryJsonFileHasTheFormatsFieldsTypesAndShapes) {
  test::TempDir out;
  ExportOptions options;
  options.format = ExportFormat::kBop;
  options.bop.split = "val";
  options.bop.scene_id = 12;
  ASSERT_TRUE(ExportAnnotation(Sequence(), Annotation(), out.path(), options).ok());
  const std::string scene = out.File("val/000012");
  for (const char* cam : {"_cam0", "_cam1"}) {
    const Json cameras = ReadJson(fmt::format("{}/scene_camera{}.json", scene, cam));
    const Json gts = ReadJson(fmt::format("{}/scene_gt{}.json", scene, cam));
    const Json infos = ReadJson(fmt::format("{}/scene_gt_info{}.json", scene, cam));
    ExpectImageIds(cameras, kFrames, "scene_camera");
    ExpectImageIds(gts, kFrames, "scene_gt");
    ExpectImageIds(infos, kFrames, "scene_gt_info");
    for (int image = 0; image < kFrames; ++image) {
      const std::string id = std::to_string(image);
      const Json& camera = cameras.at(id);
      EXPECT_EQ(Keys(camera), (std::vector<std::string>{"cam_K", "cam_R_w2c", "cam_t_w2c"}));
      ExpectNumbers(camera.at("cam_K"), 9, "cam_K");
      ExpectNumbers(camera.at("cam_R_w2c"), 9, "cam_R_w2c");
      ExpectNumbers(camera.at("cam_t_w2c"), 3, "cam_t_w2c");
      const Eigen::Matrix3d K = Matrix3(camera.at("cam_K"));
      EXPECT_EQ(K(1, 0), 0.0);
      EXPECT_EQ(K(2, 0), 0.0);
      EXPECT_EQ(K(2, 1), 0.0);
      EXPECT_EQ(K(2, 2), 1.0);

      ASSERT_TRUE(gts.at(id).is_array());
      ASSERT_EQ(gts.at(id).size(), 1u);
      const Json& gt = gts.at(id).at(0);
      EXPECT_EQ(Keys(gt), (std::vector<std::string>{"cam_R_m2c", "cam_t_m2c", "obj_id"}));
      EXPECT_TRUE(gt.at("obj_id").is_number_integer());
      ExpectNumbers(gt.at("cam_R_m2c"), 9, "cam_R_m2c");
      ExpectNumbers(gt.at("cam_t_m2c"), 3, "cam_t_m2c");
      const Eigen::Matrix3d R = Matrix3(gt.at("cam_R_m2c"));
      EXPECT_TRUE((R * R.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-9));
      EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
      EXPECT_GT(Vector3(gt.at("cam_t_m2c")).z(), 100.0);  // mm: the object is 400 mm away

      ASSERT_TRUE(infos.at(id).is_array());
      ASSERT_EQ(infos.at(id).size(), 1u);
      const Json& info = infos.at(id).at(0);
      EXPECT_EQ(Keys(info),
                (std::vector<std::string>{"bbox_obj", "bbox_visib", "px_count_all",
                                          "px_count_valid", "px_count_visib", "visib_fract"}));
      ExpectIntegers(info.at("bbox_obj"), 4, "bbox_obj");
      ExpectIntegers(info.at("bbox_visib"), 4, "bbox_visib");
      for (const char* count : {"px_count_all", "px_count_valid", "px_count_visib"}) {
        EXPECT_TRUE(info.at(count).is_number_integer()) << count;
      }
      EXPECT_TRUE(info.at("visib_fract").is_number());
      const double fraction = info.at("visib_fract").get<double>();
      EXPECT_GT(fraction, 0.0);
      EXPECT_LE(fraction, 1.0);
      EXPECT_GE(info.at("px_count_all").get<int>(), info.at("px_count_visib").get<int>());
      EXPECT_EQ(info.at("px_count_valid").get<int>(), 0);  // no depth
      EXPECT_TRUE(fs::exists(fmt::format("{}/rgb{}/{:06d}.png", scene, cam, image)));
      EXPECT_TRUE(fs::exists(fmt::format("{}/mask{}/{:06d}_000000.png", scene, cam, image)));
    }
  }
  const Json models = ReadJson(out.File("models/models_info.json"));
  ASSERT_TRUE(models.is_object());
  EXPECT_EQ(Keys(models), (std::vector<std::string>{"1"}));
  EXPECT_EQ(Keys(models.at("1")), (std::vector<std::string>{"diameter", "min_x", "min_y", "min_z",
                                                            "size_x", "size_y", "size_z"}));
  for (auto it = models.at("1").begin(); it != models.at("1").end(); ++it) {
    EXPECT_TRUE(it.value().is_number()) << it.key();
  }
}

INSTANTIATE_TEST_SUITE_P(PinholeAndDistorted, BopWriterTest, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "Distorted" : "Pinhole"; });

TEST(BopWriterFramesTest, FrameRangeStepAndOneCameraWithoutSuffix) {
  test::TempDir dir;
  SynthesizeSequence(dir.File("seq"), /*distorted=*/false);
  test::TempDir out;
  ExportOptions options;
  options.format = ExportFormat::kBop;
  options.cameras = {"cam1"};
  options.first_frame = 1;
  options.frame_step = 2;
  const StatusOr<ExportSummary> summary =
      ExportAnnotation(dir.File("seq"), dir.File("seq/gt"), out.path(), options);
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->frames, (std::vector<int>{1, 3}));
  const std::string scene = out.File("test/000000");
  EXPECT_TRUE(fs::exists(scene + "/rgb/000001.png"));
  EXPECT_FALSE(fs::exists(scene + "/rgb/000002.png"));
  EXPECT_FALSE(fs::exists(scene + "/rgb_cam1"));
  // Image 1 is frame 3: cam_from_model = cam_from_template · template_from_bboxcentre.
  const StatusOr<std::vector<Eigen::Isometry3d>> gt =
      ReadPoseFile(dir.File("seq/gt/cam1/pose.txt"));
  ASSERT_TRUE(gt.ok());
  const Json gt_json = ReadJson(scene + "/scene_gt.json").at("1").at(0);
  const PlyModel model = ReadAsciiPly(out.File("models/obj_000001.ply"));
  const StatusOr<::bcot::Sequence> sequence = LoadSequence(dir.File("seq"), false);
  ASSERT_TRUE(sequence.ok());
  const StatusOr<Mesh> mesh = Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
  ASSERT_TRUE(mesh.ok());
  const Eigen::Vector3d centre = mesh->bbox_center();
  // A model vertex v (bbox-centred) is the template point v + centre.
  const Eigen::Vector3d expected = (*gt)[3] * (model.vertices[0] + centre);
  const Eigen::Vector3d actual =
      Matrix3(gt_json.at("cam_R_m2c")) * model.vertices[0] + Vector3(gt_json.at("cam_t_m2c"));
  EXPECT_LT((expected - actual).norm(), 1e-3);

  // Exporting again into the same scene needs overwrite.
  EXPECT_EQ(
      ExportAnnotation(dir.File("seq"), dir.File("seq/gt"), out.path(), options).status().code(),
      StatusCode::kInvalidConfig);
  options.overwrite = true;
  EXPECT_TRUE(ExportAnnotation(dir.File("seq"), dir.File("seq/gt"), out.path(), options).ok());

  options.first_frame = 4;  // the sequence has 4 frames
  const Status status =
      ExportAnnotation(dir.File("seq"), dir.File("seq/gt"), out.path(), options).status();
  EXPECT_EQ(status.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(status.message(), HasSubstr("4 frames"));
}

TEST(BopWriterSymmetryTest, ABodyOfRevolutionListsItsAxisInModelsInfo) {
  test::TempDir dir;
  SynthOptions synth = test::SmallBinocularSynthOptions(160, 128, 1);
  synth.object.mesh = test::SourcePath("data/meshes/spool.off");
  synth.object.size_mm = 120.0;
  ASSERT_TRUE(Synthesize(synth, dir.File("seq")).ok());
  for (const bool listed : {true, false}) {
    test::TempDir out;
    ExportOptions options;
    options.format = ExportFormat::kBop;
    options.bop.symmetries_continuous = listed;
    ASSERT_TRUE(ExportAnnotation(dir.File("seq"), dir.File("seq/gt"), out.path(), options).ok());
    const Json info = ReadJson(out.File("models/models_info.json")).at("1");
    ASSERT_EQ(info.contains("symmetries_continuous"), listed);
    if (!listed) continue;
    const Json& symmetry = info.at("symmetries_continuous").at(0);
    ExpectNumbers(symmetry.at("axis"), 3, "axis");
    ExpectNumbers(symmetry.at("offset"), 3, "offset");
    // The spool's axis is its mesh's x axis; BOP's model frame only moves the origin.
    const Eigen::Vector3d axis(symmetry.at("axis")[0].get<double>(),
                               symmetry.at("axis")[1].get<double>(),
                               symmetry.at("axis")[2].get<double>());
    EXPECT_GT(std::abs(axis.normalized().x()), 1.0 - 1e-6);
    // The offset is a point on the axis: turning the model about it keeps its vertices on the
    // model (checked on the PLY's vertices through their distance to the axis, which a turn
    // keeps, and which must match the ring radii of the original).
    const Eigen::Vector3d offset(symmetry.at("offset")[0].get<double>(),
                                 symmetry.at("offset")[1].get<double>(),
                                 symmetry.at("offset")[2].get<double>());
    const PlyModel model = ReadAsciiPly(out.File("models/obj_000001.ply"));
    double largest = 0.0, smallest_at_rim = 1e9;
    for (const Eigen::Vector3d& v : model.vertices) {
      const double radius = (v - offset).cross(axis.normalized()).norm();
      largest = std::max(largest, radius);
    }
    for (const Eigen::Vector3d& v : model.vertices) {
      const double radius = (v - offset).cross(axis.normalized()).norm();
      if (radius > 0.99 * largest) smallest_at_rim = std::min(smallest_at_rim, radius);
    }
    // Every vertex of the outer rim at the same distance from the axis, to 0.1 %.
    EXPECT_GT(smallest_at_rim, 0.999 * largest);
  }
}

}  // namespace
}  // namespace bcot
