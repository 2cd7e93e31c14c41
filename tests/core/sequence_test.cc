#include "bcot/core/sequence.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/rig_io.h"
#include "test_util.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;
using test::PoseNear;
using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Writes empty image files `000000<extension>` ... for frames [0, count) into `folder`. The
// sequence loader only lists images; decoding them is the pipeline's job.
void WriteFrames(const std::string& folder, int count, const std::string& extension = ".png",
                 int width = 6) {
  for (int i = 0; i < count; ++i) {
    test::WriteText(fmt::format("{}/{:0{}}{}", folder, i, width, extension), "");
  }
}

// A valid sequence in a temporary directory: cameras cam0 and cam1 with 3 frames each,
// object.yaml with its mesh, init_pose.txt and timestamps.csv.
class SequenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Rig rig;
    rig.Add({Camera("cam0", 640, 512, 500, 500, 319.5, 255.5), Eigen::Isometry3d::Identity()});
    Eigen::Isometry3d cam1_from_rig = Eigen::Isometry3d::Identity();
    cam1_from_rig.translation() = Eigen::Vector3d(-120.0, 0.0, 0.0);
    rig.Add({Camera("cam1", 640, 512, 505, 505, 320.5, 256.5), cam1_from_rig});
    ASSERT_TRUE(WriteRigYaml(File("rig.yaml"), rig).ok());
    test::WriteText(File("object.yaml"), "name: cat\nmesh: ../models/cat.obj\n");
    test::WriteText(dir_.File("models/cat.obj"), "v 0 0 0\n");
    WriteFrames(File("cam0"), 3);
    WriteFrames(File("cam1"), 3);
    init_rig_from_object_ = Eigen::Isometry3d::Identity();
    init_rig_from_object_.translation() = Eigen::Vector3d(10.0, -20.0, 600.0);
    ASSERT_TRUE(WritePoseFile(File("init_pose.txt"), {init_rig_from_object_}).ok());
    test::WriteText(File("timestamps.csv"),
                    "frame,cam0,cam1\n0,1000,1003\n1,34333333,34333336\n2,67666666,67666670\n");
  }

  std::string File(const std::string& name) const { return seq_dir() + "/" + name; }
  std::string seq_dir() const { return dir_.File("seq"); }

  StatusOr<Sequence> Load(bool require_init_pose = true) const {
    return LoadSequence(seq_dir(), require_init_pose);
  }

  test::TempDir dir_;
  Eigen::Isometry3d init_rig_from_object_;
};

TEST_F(SequenceTest, LoadsValidSequence) {
  const StatusOr<Sequence> sequence = Load();
  ASSERT_TRUE(sequence.ok()) << sequence.status().message();
  EXPECT_EQ(sequence->dir, seq_dir());
  ASSERT_EQ(sequence->rig.size(), 2);
  EXPECT_EQ(sequence->rig[1].camera.name, "cam1");
  EXPECT_EQ(sequence->object.name, "cat");
  EXPECT_TRUE(fs::is_regular_file(sequence->object.mesh_path));
  EXPECT_EQ(sequence->num_frames, 3);
  ASSERT_EQ(sequence->image_paths.size(), 2u);
  EXPECT_THAT(
      sequence->image_paths[0],
      ElementsAre(File("cam0/000000.png"), File("cam0/000001.png"), File("cam0/000002.png")));
  EXPECT_THAT(
      sequence->image_paths[1],
      ElementsAre(File("cam1/000000.png"), File("cam1/000001.png"), File("cam1/000002.png")));
  ASSERT_TRUE(sequence->init_rig_from_object.has_value());
  EXPECT_THAT(*sequence->init_rig_from_object, PoseNear(init_rig_from_object_, 0.0, 0.0));
  ASSERT_EQ(sequence->timestamps_ns.size(), 3u);
  EXPECT_THAT(sequence->timestamps_ns[0], ElementsAre(1000, 1003));
  EXPECT_THAT(sequence->timestamps_ns[2], ElementsAre(67666666, 67666670));
}

TEST_F(SequenceTest, TimestampsAreOptional) {
  fs::remove(File("timestamps.csv"));
  const StatusOr<Sequence> sequence = Load();
  ASSERT_TRUE(sequence.ok()) << sequence.status().message();
  EXPECT_TRUE(sequence->timestamps_ns.empty());
}

TEST_F(SequenceTest, TimestampsWithoutHeaderAndWithCrlf) {
  test::WriteText(File("timestamps.csv"), "0, 5, 6\r\n1, 7, 8\r\n2, 9, 10\r\n\r\n");
  const StatusOr<Sequence> sequence = Load();
  ASSERT_TRUE(sequence.ok()) << sequence.status().message();
  ASSERT_EQ(sequence->timestamps_ns.size(), 3u);
  EXPECT_THAT(sequence->timestamps_ns[1], ElementsAre(7, 8));
}

TEST_F(SequenceTest, InitPoseRequiredOrOptional) {
  fs::remove(File("init_pose.txt"));
  const StatusOr<Sequence> required = Load(true);
  ASSERT_FALSE(required.ok());
  EXPECT_EQ(required.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(required.status().message(), HasSubstr(File("init_pose.txt")));

  const StatusOr<Sequence> optional = Load(false);
  ASSERT_TRUE(optional.ok()) << optional.status().message();
  EXPECT_FALSE(optional->init_rig_from_object.has_value());
}

TEST_F(SequenceTest, InitPoseMustHoldExactlyOnePose) {
  test::WriteText(File("init_pose.txt"), "1 0 0 0 1 0 0 0 1 0 0 500\n1 0 0 0 1 0 0 0 1 0 0 510\n");
  StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("init_pose.txt") + ":2: "),
                    HasSubstr("expected exactly one pose line"), HasSubstr("got 2")));

  test::WriteText(File("init_pose.txt"), "\n");
  sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("init_pose.txt") + ": "), HasSubstr("got 0")));
}

TEST_F(SequenceTest, InitPoseErrorsNameTheLine) {
  test::WriteText(File("init_pose.txt"), "1 0 0 0 2 0 0 0 1 0 0 500\r\n");
  const StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("init_pose.txt") + ":1: "), HasSubstr("orthonormal")));
}

TEST_F(SequenceTest, MissingCameraFolder) {
  fs::remove_all(File("cam1"));
  const StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("cam1") + ": "), HasSubstr("camera 'cam1'"),
                    HasSubstr("cameras[1]"), HasSubstr("not found")));
}

TEST_F(SequenceTest, CameraFolderThatIsAFileOrEmpty) {
  fs::remove_all(File("cam1"));
  test::WriteText(File("cam1"), "");
  StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("cam1") + ": "), HasSubstr("expected a folder")));

  fs::remove(File("cam1"));
  fs::create_directory(File("cam1"));
  sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("cam1") + ": "), HasSubstr("no frame images")));
}

TEST_F(SequenceTest, MismatchedFrameCountsNameBothCamerasAndCounts) {
  WriteFrames(File("cam1"), 5);
  const StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(sequence.status().message(),
              AllOf(HasSubstr(seq_dir()), HasSubstr("camera 'cam1' has 5 frames"),
                    HasSubstr("camera 'cam0' has 3")));
}

TEST_F(SequenceTest, GapInACameraFolder) {
  fs::remove(File("cam0/000001.png"));
  const StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("cam0") + ": "), HasSubstr("frame 1 is missing")));
}

TEST_F(SequenceTest, MissingRigYamlOrObjectYamlOrMesh) {
  fs::remove(dir_.File("models/cat.obj"));
  StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(sequence.status().message(),
              AllOf(StartsWith(File("object.yaml") + ":2: mesh: "), HasSubstr("cat.obj")));

  fs::remove(File("object.yaml"));
  sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(sequence.status().message(), HasSubstr(File("object.yaml")));

  fs::remove(File("rig.yaml"));
  sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(sequence.status().message(), HasSubstr(File("rig.yaml")));
}

TEST_F(SequenceTest, InvalidRigYamlIsReportedWithItsLine) {
  test::WriteText(File("rig.yaml"), "cameras:\n  - name: cam0\n    focal: 3\n");
  const StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(sequence.status().message(), StartsWith(File("rig.yaml") + ":"));
}

TEST_F(SequenceTest, MissingSequenceDirectory) {
  const StatusOr<Sequence> sequence = LoadSequence(dir_.File("nope"));
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(sequence.status().message(), HasSubstr(dir_.File("nope")));
}

struct BadTimestampsCase {
  std::string text;
  int line;  // 0: no line expected
  std::string problem;
};

class BadTimestampsTest : public SequenceTest,
                          public ::testing::WithParamInterface<BadTimestampsCase> {};

TEST_P(BadTimestampsTest, MessageNamesFileLineAndProblem) {
  const BadTimestampsCase& c = GetParam();
  test::WriteText(File("timestamps.csv"), c.text);
  const StatusOr<Sequence> sequence = Load();
  ASSERT_FALSE(sequence.ok()) << c.text;
  EXPECT_EQ(sequence.status().code(), StatusCode::kInvalidInput);
  const std::string where = c.line > 0 ? fmt::format("{}:{}: ", File("timestamps.csv"), c.line)
                                       : File("timestamps.csv") + ": ";
  EXPECT_THAT(sequence.status().message(), AllOf(StartsWith(where), HasSubstr(c.problem)));
}

INSTANTIATE_TEST_SUITE_P(
    Errors, BadTimestampsTest,
    ::testing::Values(
        BadTimestampsCase{"frame,cam0,cam1\n0,1,2\n1,3\n2,5,6\n", 3,
                          "expected 3 comma-separated fields (frame, then one nanosecond stamp "
                          "per camera: cam0, cam1), got 2"},
        BadTimestampsCase{"0,1,2\n2,3,4\n1,5,6\n", 2, "frame index 2, expected 1"},
        BadTimestampsCase{"0,1,2\n1,3,x\n2,5,6\n", 2, "stamp of camera 'cam1' is 'x'"},
        BadTimestampsCase{"0,1,2\n1,3.5,4\n2,5,6\n", 2, "stamp of camera 'cam0' is '3.5'"},
        BadTimestampsCase{"0,1,2\n1,3,4\nz,5,6\n", 3, "frame index 'z' is not an integer"},
        BadTimestampsCase{"0,1,2\n1,3,4\n", 2, "2 timestamp rows, expected 3"},
        BadTimestampsCase{"0,1,2\n1,3,4\n2,5,6\n3,7,8\n", 4,
                          "row for frame 3, but the camera folders hold only 3 frames"},
        BadTimestampsCase{"0,1,2\n\n1,3,4\n2,5,6\n", 2, "blank line"},
        BadTimestampsCase{"frame,cam1,cam0\n0,1,2\n1,3,4\n2,5,6\n", 1,
                          "column 2 is camera 'cam1', but rig.yaml lists 'cam0' there"},
        BadTimestampsCase{"frame,cam0\n0,1\n1,3\n2,5\n", 1, "header has 2 columns, expected 3"},
        BadTimestampsCase{"", 0, "0 timestamp rows, expected 3"},
        BadTimestampsCase{"frame,cam0,cam1\n", 1, "0 timestamp rows, expected 3"}));

// ---------------------------------------------------------------------------------------------
// ListFrameImages

TEST(ListFrameImagesTest, ListsInNumericOrderAndIgnoresOtherFiles) {
  test::TempDir dir;
  // Unpadded names: lexicographic order would put 10 before 2.
  WriteFrames(dir.path(), 12, ".jpg", 1);
  test::WriteText(dir.File("pose.txt"), "");
  test::WriteText(dir.File(".hidden.png"), "");
  test::WriteText(dir.File("notes.md"), "");
  fs::create_directory(dir.File("thumbs"));
  const auto images = ListFrameImages(dir.path());
  ASSERT_TRUE(images.ok()) << images.status().message();
  ASSERT_EQ(images->size(), 12u);
  for (int i = 0; i < 12; ++i) EXPECT_EQ((*images)[i], dir.File(fmt::format("{}.jpg", i)));
}

TEST(ListFrameImagesTest, AcceptsJpegAndUppercaseExtensions) {
  for (const std::string extension : {".jpeg", ".PNG", ".JPG"}) {
    test::TempDir dir;
    WriteFrames(dir.path(), 2, extension);
    const auto images = ListFrameImages(dir.path());
    ASSERT_TRUE(images.ok()) << extension << ": " << images.status().message();
    EXPECT_THAT(*images,
                ElementsAre(dir.File("000000" + extension), dir.File("000001" + extension)));
  }
}

TEST(ListFrameImagesTest, PaddingGrowsOnlyWhenTheIndexNeedsIt) {
  test::TempDir dir;
  WriteFrames(dir.path(), 10, ".png", 1);
  test::WriteText(dir.File("10.png"), "");  // 2 digits because 10 needs them
  const auto images = ListFrameImages(dir.path());
  ASSERT_TRUE(images.ok()) << images.status().message();
  EXPECT_EQ(images->size(), 11u);
}

TEST(ListFrameImagesTest, RealBcotFolderWithFourDigitNames) {
  const std::string folder = test::SharedDataPath("bcot_real_cat/handheld_demo/Cat");
  if (folder.empty()) GTEST_SKIP() << "shared BCOT data not available";
  const auto images = ListFrameImages(folder);
  ASSERT_TRUE(images.ok()) << images.status().message();
  ASSERT_EQ(images->size(), 31u);  // pose.txt beside the frames is ignored
  EXPECT_EQ(fs::path(images->front()).filename(), "0000.png");
  EXPECT_EQ(fs::path(images->back()).filename(), "0030.png");
}

TEST(ListFrameImagesTest, GapNamesFolderAndNeighbours) {
  test::TempDir dir;
  WriteFrames(dir.path(), 8);
  fs::remove(dir.File("000005.png"));
  fs::remove(dir.File("000006.png"));
  const auto images = ListFrameImages(dir.path());
  ASSERT_FALSE(images.ok());
  EXPECT_EQ(images.status().code(), StatusCode::kInvalidInput);
  EXPECT_EQ(images.status().message(),
            dir.path() + ": frame 5 is missing ('000004.png' is followed by '000007.png')");
}

TEST(ListFrameImagesTest, NumberingMustStartAtZero) {
  test::TempDir dir;
  test::WriteText(dir.File("000001.png"), "");
  test::WriteText(dir.File("000002.png"), "");
  const auto images = ListFrameImages(dir.path());
  ASSERT_FALSE(images.ok());
  EXPECT_THAT(images.status().message(),
              AllOf(StartsWith(dir.path() + ": "), HasSubstr("frame 0 is missing"),
                    HasSubstr("'000001.png'")));
}

TEST(ListFrameImagesTest, NumberingMayStartAnywhereWhenAsked) {
  test::TempDir dir;
  test::WriteText(dir.File("000120.png"), "");
  test::WriteText(dir.File("000121.png"), "");
  test::WriteText(dir.File("000123.png"), "");
  int64_t first = -1;
  auto images = ListFrameImages(dir.path(), &first);
  ASSERT_FALSE(images.ok());
  EXPECT_THAT(images.status().message(), HasSubstr("frame 122 is missing"));
  test::WriteText(dir.File("000122.png"), "");
  images = ListFrameImages(dir.path(), &first);
  ASSERT_TRUE(images.ok()) << images.status().message();
  EXPECT_EQ(first, 120);
  ASSERT_EQ(images->size(), 4u);
  EXPECT_THAT(images->front(), HasSubstr("000120.png"));
}

TEST(ListFrameImagesTest, MixedExtensionsAreRejected) {
  test::TempDir dir;
  test::WriteText(dir.File("000000.png"), "");
  test::WriteText(dir.File("000001.jpg"), "");
  const auto images = ListFrameImages(dir.path());
  ASSERT_FALSE(images.ok());
  EXPECT_THAT(images.status().message(),
              AllOf(StartsWith(dir.path() + ": "), HasSubstr("different extensions")));
}

TEST(ListFrameImagesTest, ImageNotNamedByIndexIsRejected) {
  test::TempDir dir;
  WriteFrames(dir.path(), 2);
  test::WriteText(dir.File("frame_2.png"), "");
  const auto images = ListFrameImages(dir.path());
  ASSERT_FALSE(images.ok());
  EXPECT_THAT(images.status().message(),
              AllOf(StartsWith(dir.path() + ": "), HasSubstr("'frame_2.png'"),
                    HasSubstr("not named by its frame index")));
}

TEST(ListFrameImagesTest, InconsistentPaddingAndDuplicatesAreRejected) {
  test::TempDir dir;
  WriteFrames(dir.path(), 3);
  test::WriteText(dir.File("0003.png"), "");
  auto images = ListFrameImages(dir.path());
  ASSERT_FALSE(images.ok());
  EXPECT_THAT(images.status().message(),
              AllOf(HasSubstr("'0003.png' is not padded like frame 0 '000000.png'"),
                    HasSubstr("expected '000003.png'")));

  test::TempDir dup;
  WriteFrames(dup.path(), 3, ".png", 1);
  test::WriteText(dup.File("01.png"), "");
  images = ListFrameImages(dup.path());
  ASSERT_FALSE(images.ok());
  EXPECT_THAT(images.status().message(),
              AllOf(HasSubstr("'01.png'"), HasSubstr("'1.png'"), HasSubstr("both frame 1")));
}

TEST(ListFrameImagesTest, EmptyOrMissingFolder) {
  test::TempDir dir;
  test::WriteText(dir.File("readme.txt"), "");
  auto images = ListFrameImages(dir.path());
  ASSERT_FALSE(images.ok());
  EXPECT_EQ(images.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(images.status().message(),
              AllOf(StartsWith(dir.path() + ": "), HasSubstr("no frame images")));

  images = ListFrameImages(dir.File("absent"));
  ASSERT_FALSE(images.ok());
  EXPECT_EQ(images.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(images.status().message(), HasSubstr(dir.File("absent")));
}

}  // namespace
}  // namespace bcot
