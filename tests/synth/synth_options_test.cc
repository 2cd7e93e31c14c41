#include "bcot/synth/synth_options.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

TEST(SynthOptionsTest, DefaultsValidate) {
  const SynthOptions options;
  const Status status = options.Validate();
  EXPECT_TRUE(status.ok()) << status.message();
}

TEST(SynthOptionsTest, EveryBundledConfigLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::SourcePath("configs/synth"))) {
    if (entry.path().extension() != ".yaml") continue;
    ++count;
    const StatusOr<SynthOptions> options = ReadSynthOptions(entry.path().string());
    ASSERT_TRUE(options.ok()) << entry.path() << ": " << options.status().message();
    if (!options->object.mesh.empty()) {
      EXPECT_TRUE(std::filesystem::exists(options->object.mesh)) << options->object.mesh;
    }
    for (const std::string& mesh : options->distractors.meshes) {
      EXPECT_TRUE(std::filesystem::exists(mesh)) << mesh;
    }
  }
  EXPECT_GE(count, 6);
}

TEST(SynthOptionsTest, ReadsValuesAndResolvesPathsAgainstTheConfig) {
  test::TempDir dir;
  test::WriteText(dir.File("configs/a.yaml"),
                  "seed: 42\n"
                  "object:\n"
                  "  mesh: ../meshes/thing.obj\n"
                  "  size_mm: 120\n"
                  "  color_rgb: [10, 20, 30]\n"
                  "cameras:\n"
                  "  arc_angles_deg: [30, 90]\n"
                  "  cone_angles_deg: [45]\n"
                  "motion:\n"
                  "  mode: rig\n"
                  "background:\n"
                  "  kinds: [image, plain]\n"
                  "  images: [photos/wall.jpg]\n");
  const StatusOr<SynthOptions> options = ReadSynthOptions(dir.File("configs/a.yaml"));
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->seed, 42);
  EXPECT_EQ(options->object.mesh, dir.File("meshes/thing.obj"));
  EXPECT_EQ(options->object.size_mm, 120.0);
  EXPECT_EQ(options->object.color_rgb[2], 30.0);
  EXPECT_EQ(options->cameras.arc_angles_deg, (std::vector<double>{30.0, 90.0}));
  EXPECT_EQ(options->cameras.cone_angles_deg, (std::vector<double>{45.0}));
  EXPECT_EQ(options->motion.mode, "rig");
  ASSERT_EQ(options->background.images.size(), 1u);
  EXPECT_EQ(options->background.images[0], dir.File("configs/photos/wall.jpg"));
  // Untouched keys keep their defaults.
  EXPECT_EQ(options->cameras.width, SynthOptions().cameras.width);
}

TEST(SynthOptionsTest, UnknownKeyIsAnInvalidConfigNamingFileLineAndKey) {
  test::TempDir dir;
  const std::string path = dir.File("bad.yaml");
  test::WriteText(path, "object:\n  size_mm: 100\n  colour_rgb: [1, 2, 3]\n");
  const StatusOr<SynthOptions> options = ReadSynthOptions(path);
  ASSERT_FALSE(options.ok());
  test::ExpectErrorNaming(options.status(), StatusCode::kInvalidConfig,
                          {"bad.yaml:3", "colour_rgb"});

  test::WriteText(path, "motion:\n  mode: free\nsensors:\n  gamma: 2\n");
  const StatusOr<SynthOptions> section = ReadSynthOptions(path);
  ASSERT_FALSE(section.ok());
  test::ExpectErrorNaming(section.status(), StatusCode::kInvalidConfig, {"bad.yaml:3", "sensors"});
}

TEST(SynthOptionsTest, WrongTypeIsAnInvalidConfig) {
  test::TempDir dir;
  const std::string path = dir.File("bad.yaml");
  test::WriteText(path, "cameras:\n  width: wide\n");
  const StatusOr<SynthOptions> options = ReadSynthOptions(path);
  ASSERT_FALSE(options.ok());
  test::ExpectErrorNaming(options.status(), StatusCode::kInvalidConfig, {"bad.yaml:2", "width"});
}

TEST(SynthOptionsTest, ListsEveryOutOfRangeValueWithItsLine) {
  test::TempDir dir;
  const std::string path = dir.File("range.yaml");
  test::WriteText(path,
                  "object:\n"
                  "  size_mm: -3\n"
                  "cameras:\n"
                  "  hfov_deg: 200\n"
                  "  cone_angles_deg: [30, 130]\n"
                  "motion:\n"
                  "  mode: fly\n"
                  "  fps: 0\n"
                  "background:\n"
                  "  kinds: [plain, marble]\n");
  const StatusOr<SynthOptions> options = ReadSynthOptions(path);
  ASSERT_FALSE(options.ok());
  test::ExpectErrorNaming(
      options.status(), StatusCode::kInvalidConfig,
      {"range.yaml:2: object.size_mm = -3, must be in [0, 5000]",
       "range.yaml:4: cameras.hfov_deg = 200", "range.yaml:5: cameras.cone_angles_deg[1] = 130",
       "range.yaml:7: motion.mode = 'fly'", "range.yaml:8: motion.fps = 0",
       "range.yaml:10: background.kinds[1] = 'marble'"});
  EXPECT_EQ(options.status().message().find('\n'), std::string::npos) << "one line";

  SynthOptions direct;
  direct.render.object_samples_per_axis = 0;
  direct.distractors.size_min_mm = 100;
  direct.distractors.size_max_mm = 50;
  test::ExpectErrorNaming(direct.Validate(), StatusCode::kInvalidConfig,
                          {"render.object_samples_per_axis = 0", "distractors.size_max_mm = 50"});
}

TEST(SynthOptionsTest, OverridesApplyAndAreValidated) {
  const std::string demo = test::SourcePath("configs/synth/demo.yaml");
  const StatusOr<SynthOptions> options =
      ReadSynthOptions(demo, {"motion.num_frames=7", "cameras.arc_angles_deg=[30, 60]",
                              "light.moves=true", "object.name=rabbit"});
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->motion.num_frames, 7);
  EXPECT_EQ(options->cameras.arc_angles_deg, (std::vector<double>{30.0, 60.0}));
  EXPECT_TRUE(options->light.moves);
  EXPECT_EQ(options->object.name, "rabbit");

  const StatusOr<SynthOptions> unknown = ReadSynthOptions(demo, {"motion.warp=9"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(unknown.status().message(), HasSubstr("warp"));

  const StatusOr<SynthOptions> range = ReadSynthOptions(demo, {"motion.num_frames=0"});
  ASSERT_FALSE(range.ok());
  EXPECT_THAT(range.status().message(), HasSubstr("motion.num_frames = 0"));

  // No config: defaults plus overrides.
  const StatusOr<SynthOptions> defaults = ReadSynthOptions("", {"cameras.width=320"});
  ASSERT_TRUE(defaults.ok()) << defaults.status().message();
  EXPECT_EQ(defaults->cameras.width, 320);
}

TEST(SynthOptionsTest, FormatRoundTrips) {
  StatusOr<SynthOptions> read =
      ReadSynthOptions(test::SourcePath("configs/synth/glossy_fast.yaml"));
  ASSERT_TRUE(read.ok()) << read.status().message();
  SynthOptions options = *read;
  options.object.name = "yes";  // a YAML 1.1 boolean spelling must stay a string
  options.cameras.distortion = {-0.1, 0.0125, 1e-4, 0.0, 0.3};
  options.background.kinds = {"image"};
  options.background.images = {"/some where/photo \"1\".jpg"};
  options.motion.fps = 29.97;
  options.output.write_coverage = true;
  const std::string text = FormatSynthOptions(options);

  test::TempDir dir;
  test::WriteText(dir.File("sub/resolved.yaml"), text);
  const StatusOr<SynthOptions> again = ReadSynthOptions(dir.File("sub/resolved.yaml"));
  ASSERT_TRUE(again.ok()) << again.status().message() << "\n" << text;
  EXPECT_EQ(FormatSynthOptions(*again), text);
  EXPECT_EQ(again->object.name, "yes");
  EXPECT_EQ(again->cameras.distortion, options.cameras.distortion);
  EXPECT_EQ(again->object.mesh, options.object.mesh);
  EXPECT_EQ(again->motion.fps, 29.97);

  // Defaults round-trip too.
  test::WriteText(dir.File("defaults.yaml"), FormatSynthOptions(SynthOptions()));
  const StatusOr<SynthOptions> defaults = ReadSynthOptions(dir.File("defaults.yaml"));
  ASSERT_TRUE(defaults.ok()) << defaults.status().message();
  EXPECT_EQ(FormatSynthOptions(*defaults), FormatSynthOptions(SynthOptions()));
}

}  // namespace
}  // namespace bcot
