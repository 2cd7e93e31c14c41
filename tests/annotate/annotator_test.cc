#include "bcot/annotate/annotator.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "bcot/annotate/done_file.h"
#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

// A small binocular 90° sequence from the demo config: glossy object, cluttered and plain
// backgrounds, distractors, noise, blur; 480×384, 4 frames.
class AnnotatorTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    const StatusOr<SynthOptions> options =
        ReadSynthOptions(test::SourcePath("configs/synth/demo.yaml"),
                         {"cameras.width=480", "cameras.height=384", "motion.num_frames=4"});
    BCOT_CHECK(options.ok());
    BCOT_CHECK(Synthesize(*options, SequenceDir()).ok());
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string SequenceDir() { return dir_->File("seq"); }

  static test::TempDir* dir_;
};

test::TempDir* AnnotatorTest::dir_ = nullptr;

TEST_F(AnnotatorTest, AnnotatesASyntheticSequenceCloseToGroundTruth) {
  test::TempDir out;
  const std::string out_dir = out.File("ann");
  int progress_calls = 0;
  const StatusOr<AnnotationOutcome> outcome =
      AnnotateSequenceDir(SequenceDir(), out_dir, AnnotateOptions(), [&](int done, int total) {
        EXPECT_EQ(total, 4);
        EXPECT_EQ(done, ++progress_calls);
      });
  ASSERT_TRUE(outcome.ok()) << outcome.status().message();
  EXPECT_EQ(outcome->frames, 4);
  EXPECT_TRUE(outcome->verdict.accepted);
  // DONE records the hashes and the sequence, read back by its one reader.
  const StatusOr<DoneRecord> done = ReadDoneFile(out_dir);
  ASSERT_TRUE(done.ok()) << done.status().message();
  EXPECT_EQ(done->frames, 4);
  EXPECT_EQ(done->config_hash, AnnotateConfigHash(AnnotateOptions()));
  EXPECT_EQ(std::filesystem::path(done->sequence_dir).filename(),
            std::filesystem::path(SequenceDir()).filename());
  EXPECT_EQ(progress_calls, 4);
  for (const char* file : {"rig_from_object.txt", "cam0/pose.txt", "cam1/pose.txt", "frames.csv",
                           "config.resolved.yaml", "DONE"}) {
    EXPECT_TRUE(std::filesystem::exists(out_dir + "/" + file)) << file;
  }
  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(SequenceDir() + "/gt/rig_from_object.txt");
  const StatusOr<std::vector<Eigen::Isometry3d>> annotated =
      ReadPoseFile(out_dir + "/rig_from_object.txt");
  ASSERT_TRUE(truth.ok() && annotated.ok());
  ASSERT_EQ(annotated->size(), 4u);
  for (size_t f = 0; f < truth->size(); ++f) {
    // From a 5° / 5 mm initial pose at 480×384 (object ~160 px).
    std::printf("frame %zu: %.4f deg %.4f mm\n", f,
                test::RotationErrorDeg((*annotated)[f], (*truth)[f]),
                test::TranslationErrorMm((*annotated)[f], (*truth)[f]));
    EXPECT_THAT((*annotated)[f], test::PoseNear((*truth)[f], 0.5, 1.0)) << "frame " << f;
  }
  // cam_from_object = cam_from_rig · rig_from_object for every camera.
  const StatusOr<std::vector<Eigen::Isometry3d>> cam1 = ReadPoseFile(out_dir + "/cam1/pose.txt");
  const StatusOr<std::vector<Eigen::Isometry3d>> cam1_truth =
      ReadPoseFile(SequenceDir() + "/gt/cam1/pose.txt");
  ASSERT_TRUE(cam1.ok() && cam1_truth.ok());
  EXPECT_THAT((*cam1)[3], test::PoseNear((*cam1_truth)[3], 0.5, 1.0));
  EXPECT_EQ(done->failed_frames, 0);
  const StatusOr<std::string> config = ReadTextFile(out_dir + "/config.resolved.yaml");
  ASSERT_TRUE(config.ok());
  EXPECT_THAT(*config, HasSubstr("input_hash:"));
  EXPECT_THAT(*config, HasSubstr("rounds: 2"));
}

TEST_F(AnnotatorTest, MonocularSelectionUsesOneCamera) {
  StatusOr<Sequence> sequence = LoadSequence(SequenceDir());
  ASSERT_TRUE(sequence.ok());
  AnnotateOptions options;
  options.tracker.frame.rounds = 1;
  options.views.cameras = {"cam1"};
  const StatusOr<SequenceAnnotation> annotation = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(annotation.ok()) << annotation.status().message();
  ASSERT_EQ(annotation->view_names.size(), 1u);
  EXPECT_EQ(annotation->view_names[0], "cam1");
  EXPECT_EQ(annotation->frames[0].summary.views.size(), 1u);
  options.views.cameras = {"cam7"};
  const StatusOr<SequenceAnnotation> missing = AnnotateSequence(*sequence, options);
  ASSERT_EQ(missing.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(missing.status().message(), HasSubstr("no camera 'cam7' in the rig"));
}

// One note names every camera whose frames are JPEG with subsampled chroma; PNG frames and
// unreadable files give none (the solve reports those).
// One colour image as `dir`/a.jpg (OpenCV writes 4:2:0) and a.png.
void WriteJpegAndPng(const test::TempDir& dir) {
  const cv::Mat3b image(32, 48, cv::Vec3b(40, 120, 200));
  ASSERT_TRUE(cv::imwrite(dir.File("a.jpg"), image));
  ASSERT_TRUE(cv::imwrite(dir.File("a.png"), image));
}

TEST(CaptureNotesTest, NamesTheCamerasWithSubsampledChroma) {
  test::TempDir dir;
  WriteJpegAndPng(dir);
  Sequence sequence;
  for (const char* name : {"cam0", "cam1", "cam2"}) {
    sequence.rig.Add({Camera(name, 48, 32, 40.0, 40.0, 23.5, 15.5), Eigen::Isometry3d::Identity()});
  }
  sequence.image_paths = {{dir.File("a.jpg")}, {dir.File("a.png")}, {dir.File("a.jpg")}};
  const std::vector<std::string> notes = CaptureNotes(sequence);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_THAT(notes[0], ::testing::StartsWith(
                            "cam0 (4:2:0), cam2 (4:2:0): JPEG frames with subsampled chroma"));

  sequence.image_paths = {{dir.File("a.png")}, {dir.File("a.png")}, {dir.File("missing.jpg")}};
  EXPECT_TRUE(CaptureNotes(sequence).empty());
}

// The edge stage's chroma sampling per camera: from its first frame's header (auto), or as set.
TEST(ResolveChromaSamplingTest, ReadsTheFirstFrameUnlessSet) {
  test::TempDir dir;
  WriteJpegAndPng(dir);
  Sequence sequence;
  sequence.image_paths = {{dir.File("a.jpg")}, {dir.File("a.png")}, {dir.File("missing.jpg")}};
  EXPECT_EQ(ResolveChromaSampling(sequence, 0, ChromaSamplingSetting::kAuto).value(),
            ChromaSampling::Jpeg420());
  EXPECT_EQ(ResolveChromaSampling(sequence, 1, ChromaSamplingSetting::kAuto).value(),
            ChromaSampling::Full());
  EXPECT_EQ(ResolveChromaSampling(sequence, 1, ChromaSamplingSetting::kJpeg420).value(),
            ChromaSampling::Jpeg420());
  EXPECT_EQ(ResolveChromaSampling(sequence, 0, ChromaSamplingSetting::kFull).value(),
            ChromaSampling::Full());
  EXPECT_THAT(ResolveChromaSampling(sequence, 2, ChromaSamplingSetting::kAuto).status().message(),
              HasSubstr("missing.jpg: cannot read"));
}

TEST_F(AnnotatorTest, InputHashChangesWithTheInputs) {
  test::TempDir copy;
  std::filesystem::copy(SequenceDir(), copy.File("seq"), std::filesystem::copy_options::recursive);
  StatusOr<Sequence> sequence = LoadSequence(copy.File("seq"));
  ASSERT_TRUE(sequence.ok());
  const StatusOr<std::string> before = SequenceInputHash(*sequence);
  ASSERT_TRUE(before.ok());
  EXPECT_EQ(*SequenceInputHash(*sequence), *before);
  test::WriteText(copy.File("seq/init_pose.txt"),
                  FormatPoseLine(Eigen::Isometry3d(Eigen::Translation3d(1, 2, 300))) + "\n");
  EXPECT_NE(*SequenceInputHash(*sequence), *before);
}

// A keyframe is enough to start: without init_pose.txt, tracking runs backwards and forwards
// from a keyframe at frame 2 (the true pose) and every frame is as accurate as from frame 0.
TEST_F(AnnotatorTest, AKeyframeTracksBackwardsAndForwardsWithoutInitPose) {
  test::TempDir copy;
  const std::string seq = copy.File("seq");
  std::filesystem::copy(SequenceDir(), seq, std::filesystem::copy_options::recursive);
  std::filesystem::remove(seq + "/init_pose.txt");
  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(SequenceDir() + "/gt/rig_from_object.txt");
  ASSERT_TRUE(truth.ok());
  EXPECT_EQ(AnnotateSequenceDir(seq, copy.File("none"), AnnotateOptions()).status().code(),
            StatusCode::kNotFound);
  test::WriteText(seq + "/keyframes.txt", "2 " + FormatPoseLine((*truth)[2]) + "\n");
  const StatusOr<AnnotationOutcome> outcome =
      AnnotateSequenceDir(seq, copy.File("out"), AnnotateOptions());
  ASSERT_TRUE(outcome.ok()) << outcome.status().message();
  EXPECT_EQ(outcome->failed_frames, 0);
  const StatusOr<std::vector<Eigen::Isometry3d>> annotated =
      ReadPoseFile(copy.File("out/rig_from_object.txt"));
  ASSERT_TRUE(annotated.ok());
  ASSERT_EQ(annotated->size(), 4u);
  for (size_t f = 0; f < 4; ++f) {
    EXPECT_THAT((*annotated)[f], test::PoseNear((*truth)[f], 0.5, 1.0)) << "frame " << f;
  }
}

// A wrong init_pose.txt ruins the frames tracked from it; a keyframe at frame 1 restores the
// frame before it (tracked backwards) and those after it (forwards).
TEST_F(AnnotatorTest, AKeyframeMendsFramesBeforeAndAfterIt) {
  test::TempDir copy;
  const std::string seq = copy.File("seq");
  std::filesystem::copy(SequenceDir(), seq, std::filesystem::copy_options::recursive);
  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(SequenceDir() + "/gt/rig_from_object.txt");
  ASSERT_TRUE(truth.ok());
  Eigen::Isometry3d wrong = (*truth)[0];
  wrong.translation() += Eigen::Vector3d(60.0, -40.0, 0.0);
  wrong.linear() = wrong.linear() * Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitY()).matrix();
  ASSERT_TRUE(WritePoseFile(seq + "/init_pose.txt", {wrong}).ok());
  AnnotateOptions options;
  StatusOr<Sequence> sequence = LoadSequence(seq);
  ASSERT_TRUE(sequence.ok());
  const StatusOr<SequenceAnnotation> without = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(without.ok()) << without.status().message();
  EXPECT_THAT(without->rig_from_object[3], ::testing::Not(test::PoseNear((*truth)[3], 0.5, 1.0)));

  test::WriteText(copy.File("keys.txt"), "1 " + FormatPoseLine((*truth)[1]) + "\n");
  ASSERT_TRUE(LoadKeyframes(copy.File("keys.txt"), &*sequence).ok());
  const StatusOr<SequenceAnnotation> with = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(with.ok()) << with.status().message();
  // Frame 0 is as near to its init pose as to the keyframe: it keeps the init pose's solve.
  for (size_t f = 1; f < 4; ++f) {
    EXPECT_THAT(with->rig_from_object[f], test::PoseNear((*truth)[f], 0.5, 1.0)) << "frame " << f;
  }
  // With the keyframe at frame 3 instead, frame 2 (nearer to it than to frame 0) is solved
  // backwards from it; frame 1 is as near to both and keeps the init pose's.
  test::WriteText(copy.File("keys.txt"), "3 " + FormatPoseLine((*truth)[3]) + "\n");
  ASSERT_TRUE(LoadKeyframes(copy.File("keys.txt"), &*sequence).ok());
  const StatusOr<SequenceAnnotation> later = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(later.ok()) << later.status().message();
  for (size_t f = 2; f < 4; ++f) {
    EXPECT_THAT(later->rig_from_object[f], test::PoseNear((*truth)[f], 0.5, 1.0)) << "frame " << f;
  }
}

// A sequence whose object jumps (12 frames of 6° and 4 mm dropped between frames 5 and 6): a
// keyframe at frame 6 mends the frames after the jump, and the frames before it that belong to
// the keyframe (3–5, nearer to it than to frame 0) keep the forward solve from frame 0, which
// scores better than the backward track across the jump.
TEST(AnnotatorJumpTest, AKeyframeAfterAJumpKeepsTheFramesBeforeIt) {
  namespace fs = std::filesystem;
  test::TempDir dir;
  const StatusOr<SynthOptions> synth =
      ReadSynthOptions(test::SourcePath("configs/synth/demo.yaml"),
                       {"cameras.width=320", "cameras.height=256", "motion.num_frames=22",
                        "motion.rotation_deg_per_frame=6", "motion.translation_mm_per_frame=4",
                        "render.object_samples_per_axis=2"});
  ASSERT_TRUE(synth.ok()) << synth.status().message();
  ASSERT_TRUE(Synthesize(*synth, dir.File("full")).ok());
  const std::vector<int> keep = {0, 1, 2, 3, 4, 5, 18, 19, 20, 21};
  const std::string seq = dir.File("seq");
  fs::create_directories(seq);
  for (const char* name : {"rig.yaml", "object.yaml", "init_pose.txt"}) {
    fs::copy(dir.File("full/") + name, seq + "/" + name);
  }
  fs::copy(dir.File("full/model"), seq + "/model", fs::copy_options::recursive);
  for (const char* camera : {"cam0", "cam1"}) {
    fs::create_directories(seq + "/" + camera);
    for (size_t i = 0; i < keep.size(); ++i) {
      fs::copy(fmt::format("{}/{}/{:06d}.png", dir.File("full"), camera, keep[i]),
               fmt::format("{}/{}/{:06d}.png", seq, camera, i));
    }
  }
  const StatusOr<std::vector<Eigen::Isometry3d>> full_truth =
      ReadPoseFile(dir.File("full/gt/rig_from_object.txt"));
  ASSERT_TRUE(full_truth.ok());
  std::vector<Eigen::Isometry3d> truth;
  for (int frame : keep) truth.push_back((*full_truth)[frame]);

  StatusOr<Sequence> sequence = LoadSequence(seq);
  ASSERT_TRUE(sequence.ok()) << sequence.status().message();
  const AnnotateOptions options;
  const StatusOr<SequenceAnnotation> without = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(without.ok()) << without.status().message();
  EXPECT_THAT(without->rig_from_object[5], test::PoseNear(truth[5], 0.5, 1.0));
  EXPECT_THAT(without->rig_from_object[6], ::testing::Not(test::PoseNear(truth[6], 5.0, 10.0)));

  test::WriteText(dir.File("keys.txt"), "6 " + FormatPoseLine(truth[6]) + "\n");
  ASSERT_TRUE(LoadKeyframes(dir.File("keys.txt"), &*sequence).ok());
  const StatusOr<SequenceAnnotation> with = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(with.ok()) << with.status().message();
  for (size_t f = 0; f < keep.size(); ++f) {
    EXPECT_THAT(with->rig_from_object[f], test::PoseNear(truth[f], 0.5, 1.0)) << "frame " << f;
  }
}

TEST_F(AnnotatorTest, KeyframesArePartOfTheInputHash) {
  test::TempDir copy;
  const std::string seq = copy.File("seq");
  std::filesystem::copy(SequenceDir(), seq, std::filesystem::copy_options::recursive);
  StatusOr<Sequence> sequence = LoadSequence(seq);
  ASSERT_TRUE(sequence.ok());
  const std::string before = *SequenceInputHash(*sequence);
  const Eigen::Isometry3d pose(Eigen::Translation3d(1, 2, 300));
  test::WriteText(seq + "/keyframes.txt", "3 " + FormatPoseLine(pose) + "\n");
  sequence = LoadSequence(seq);
  ASSERT_TRUE(sequence.ok());
  ASSERT_EQ(sequence->keyframes.size(), 1u);
  const std::string with_keyframe = *SequenceInputHash(*sequence);
  EXPECT_NE(with_keyframe, before);
  test::WriteText(seq + "/keyframes.txt", "2 " + FormatPoseLine(pose) + "\n");
  sequence = LoadSequence(seq);
  ASSERT_TRUE(sequence.ok());
  EXPECT_NE(*SequenceInputHash(*sequence), with_keyframe);
}

// Images numbered from 7 (a cut of a longer capture) annotate as frames 0, 1, ...: the same
// poses as the sequence numbered from 0.
TEST_F(AnnotatorTest, ImageNumberingMayStartAnywhere) {
  test::TempDir copy;
  const std::string seq = copy.File("seq");
  std::filesystem::copy(SequenceDir(), seq, std::filesystem::copy_options::recursive);
  for (const char* camera : {"cam0", "cam1"}) {
    for (int f = 3; f >= 0; --f) {
      std::filesystem::rename(seq + fmt::format("/{}/{:06d}.png", camera, f),
                              seq + fmt::format("/{}/{:06d}.png", camera, f + 7));
    }
  }
  AnnotateOptions options;
  options.tracker.frame.rounds = 1;
  const StatusOr<Sequence> shifted = LoadSequence(seq);
  ASSERT_TRUE(shifted.ok()) << shifted.status().message();
  EXPECT_EQ(shifted->first_image_index, 7);
  EXPECT_EQ(shifted->num_frames, 4);
  const StatusOr<Sequence> original = LoadSequence(SequenceDir());
  ASSERT_TRUE(original.ok());
  const StatusOr<SequenceAnnotation> a = AnnotateSequence(*shifted, options);
  const StatusOr<SequenceAnnotation> b = AnnotateSequence(*original, options);
  ASSERT_TRUE(a.ok() && b.ok());
  for (size_t f = 0; f < 4; ++f) {
    EXPECT_TRUE(a->rig_from_object[f].isApprox(b->rig_from_object[f], 1e-12)) << f;
  }
}

TEST_F(AnnotatorTest, BadInputsAreErrorsNamingTheFile) {
  test::TempDir copy;
  const std::string seq = copy.File("seq");
  std::filesystem::copy(SequenceDir(), seq, std::filesystem::copy_options::recursive);
  // A mesh that does not load.
  test::WriteText(seq + "/model/bunny.obj", "this is not a mesh\n");
  const Status bad_mesh = AnnotateSequenceDir(seq, copy.File("out"), AnnotateOptions()).status();
  EXPECT_FALSE(bad_mesh.ok());
  EXPECT_THAT(bad_mesh.message(), HasSubstr("bunny.obj"));
  EXPECT_FALSE(std::filesystem::exists(copy.File("out/DONE")));
  // A corrupt image.
  std::filesystem::copy_file(SequenceDir() + "/model/bunny.obj", seq + "/model/bunny.obj",
                             std::filesystem::copy_options::overwrite_existing);
  test::WriteText(seq + "/cam1/000002.png", "not a png");
  const Status bad_image = AnnotateSequenceDir(seq, copy.File("out"), AnnotateOptions()).status();
  EXPECT_EQ(bad_image.code(), StatusCode::kInvalidInput);
  EXPECT_THAT(bad_image.message(), HasSubstr("cam1/000002.png"));
  EXPECT_FALSE(std::filesystem::exists(copy.File("out/DONE")));
}

// Found before any frame is solved: an output directory that cannot be written, and a frame-0
// pose that shows the object to no camera (behind the rig, a metre-for-millimetre slip).
TEST_F(AnnotatorTest, UnwritableOutputAndInvisibleInitialPoseFailBeforeTheSolve) {
  test::TempDir copy;
  const std::string seq = copy.File("seq");
  std::filesystem::copy(SequenceDir(), seq, std::filesystem::copy_options::recursive);
  test::WriteText(copy.File("file"), "x");
  const Status unwritable =
      AnnotateSequenceDir(seq, copy.File("file/out"), AnnotateOptions()).status();
  EXPECT_EQ(unwritable.code(), StatusCode::kIoError);
  EXPECT_THAT(unwritable.message(), HasSubstr(copy.File("file")));

  const StatusOr<std::vector<Eigen::Isometry3d>> gt =
      ReadPoseFile(SequenceDir() + "/gt/rig_from_object.txt");
  ASSERT_TRUE(gt.ok());
  for (const double z : {-1e4, 1e9}) {
    Eigen::Isometry3d pose = (*gt)[0];
    pose.translation().z() = z;
    ASSERT_TRUE(WritePoseFile(seq + "/init_pose.txt", {pose}).ok());
    const Status invisible = AnnotateSequenceDir(seq, copy.File("out"), AnnotateOptions()).status();
    EXPECT_EQ(invisible.code(), StatusCode::kInvalidInput) << z;
    EXPECT_THAT(invisible.message(), HasSubstr("init_pose.txt: the object is not in view"));
    EXPECT_THAT(invisible.message(), HasSubstr("cam0"));
    EXPECT_FALSE(std::filesystem::exists(copy.File("out/DONE")));
  }
}

// The temporal window refines the per-frame poses: both are in the annotation, the window's
// change per frame is in frames.csv and its options in config.resolved.yaml; off, the final
// poses are the per-frame ones.
TEST_F(AnnotatorTest, WindowRefinesThePerFramePosesAndIsRecorded) {
  const StatusOr<Sequence> sequence = LoadSequence(SequenceDir());
  ASSERT_TRUE(sequence.ok());
  AnnotateOptions options;
  options.tracker.frame.rounds = 2;
  options.window.enabled = false;
  const StatusOr<SequenceAnnotation> off = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(off.ok()) << off.status().message();
  options.window.enabled = true;
  options.window.size = 0;  // whole sequence
  const StatusOr<SequenceAnnotation> on = AnnotateSequence(*sequence, options);
  ASSERT_TRUE(on.ok()) << on.status().message();
  ASSERT_EQ(on->rig_from_object.size(), 4u);
  double moved_mm = 0.0;
  for (size_t f = 0; f < 4; ++f) {
    EXPECT_TRUE(off->rig_from_object[f].isApprox(off->per_frame_rig_from_object[f]));
    EXPECT_EQ(off->frames[f].window_translation_mm, 0.0);
    // The per-frame solves do not depend on the window.
    EXPECT_TRUE(on->per_frame_rig_from_object[f].isApprox(off->rig_from_object[f], 1e-9));
    EXPECT_NEAR(
        on->frames[f].window_translation_mm,
        (on->rig_from_object[f].translation() - on->per_frame_rig_from_object[f].translation())
            .norm(),
        1e-9);
    moved_mm += on->frames[f].window_translation_mm;
  }
  EXPECT_GT(moved_mm, 0.0);
  test::TempDir out;
  ASSERT_TRUE(WriteAnnotation(out.path(), *sequence, options, "0", *on).ok());
  const StatusOr<std::string> csv = ReadTextFile(out.File("frames.csv"));
  ASSERT_TRUE(csv.ok());
  EXPECT_THAT(*csv, HasSubstr(",milliseconds,window_rotation_deg,window_translation_mm\n"));
  EXPECT_THAT(*csv, HasSubstr(",edge_lines_"));
  const StatusOr<std::string> config = ReadTextFile(out.File("config.resolved.yaml"));
  ASSERT_TRUE(config.ok());
  EXPECT_THAT(*config, HasSubstr("window:\n  enabled: true\n  size: 0\n"));
}

}  // namespace
}  // namespace bcot
