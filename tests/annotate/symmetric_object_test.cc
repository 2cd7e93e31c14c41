// An object that is a body of revolution, annotated end to end: the angle about its axis, which
// no image shows, stays where the first pose put it, and the rest of the pose is as accurate as
// for any object.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "bcot/annotate/annotator.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/render/symmetry_detection.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

class SymmetricObjectTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    // The spool (a 32-sided body of revolution) turning 4° per frame about changing axes, so
    // it also turns about its own.
    const StatusOr<SynthOptions> options =
        ReadSynthOptions(test::SourcePath("configs/synth/demo.yaml"),
                         {"cameras.width=480", "cameras.height=384", "motion.num_frames=6",
                          "motion.rotation_deg_per_frame=4",
                          "object.mesh=" + test::SourcePath("data/meshes/spool.off"),
                          "object.size_mm=120", "distractors.count=0"});
    BCOT_CHECK(options.ok());
    BCOT_CHECK(Synthesize(*options, SequenceDir()).ok());
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string SequenceDir() { return dir_->File("seq"); }

  static test::TempDir* dir_;
};

test::TempDir* SymmetricObjectTest::dir_ = nullptr;

TEST_F(SymmetricObjectTest, KeepsTheAngleAboutTheAxisAndFindsTheRest) {
  test::TempDir out;
  const std::string out_dir = out.File("ann");
  const StatusOr<AnnotationOutcome> outcome =
      AnnotateSequenceDir(SequenceDir(), out_dir, AnnotateOptions(), AnnotateProgress());
  ASSERT_TRUE(outcome.ok()) << outcome.status().message();
  EXPECT_TRUE(outcome->verdict.accepted);
  EXPECT_TRUE(std::any_of(outcome->notes.begin(), outcome->notes.end(), [](const std::string& n) {
    return n.find("body of revolution") != std::string::npos;
  }));

  const StatusOr<Sequence> sequence = LoadSequence(SequenceDir(), true);
  ASSERT_TRUE(sequence.ok());
  const StatusOr<Mesh> mesh = Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
  ASSERT_TRUE(mesh.ok());
  const RayCaster caster(*mesh);
  const StatusOr<std::optional<RotationalSymmetry>> symmetry =
      DetectRotationalSymmetry(caster, SymmetryDetectionOptions());
  ASSERT_TRUE(symmetry.ok() && symmetry->has_value());
  const Eigen::Vector3d axis = (*symmetry)->axis;

  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(SequenceDir() + "/gt/rig_from_object.txt");
  const StatusOr<std::vector<Eigen::Isometry3d>> annotated =
      ReadPoseFile(out_dir + "/rig_from_object.txt");
  ASSERT_TRUE(truth.ok() && annotated.ok());
  ASSERT_EQ(annotated->size(), truth->size());
  double true_turn_deg = 0.0;
  for (size_t f = 0; f < truth->size(); ++f) {
    // Up to the turn about the axis, as accurate as the demo's bunny (AnnotatorTest).
    const Eigen::Isometry3d held = (*symmetry)->HoldAngle((*annotated)[f], (*truth)[f]);
    EXPECT_THAT(held, test::PoseNear((*truth)[f], 0.5, 1.0)) << "frame " << f;
    if (f == 0) continue;
    // Between frames the annotated object never turns about its own axis (in O_t) ...
    const Eigen::Vector3d step =
        LogSO3((*annotated)[f - 1].linear().transpose() * (*annotated)[f].linear());
    EXPECT_LT(std::abs(step.dot(axis)) * 180.0 / kPi, 1e-6) << "frame " << f;
    // ... while the true one does.
    const Eigen::Vector3d true_step =
        LogSO3((*truth)[f - 1].linear().transpose() * (*truth)[f].linear());
    true_turn_deg = std::max(true_turn_deg, std::abs(true_step.dot(axis)) * 180.0 / kPi);
  }
  EXPECT_GT(true_turn_deg, 0.2);
}

TEST_F(SymmetricObjectTest, DetectionCanBeSwitchedOff) {
  test::TempDir out;
  AnnotateOptions options;
  options.symmetry.detect = false;
  const StatusOr<AnnotationOutcome> outcome =
      AnnotateSequenceDir(SequenceDir(), out.File("ann"), options, AnnotateProgress());
  ASSERT_TRUE(outcome.ok()) << outcome.status().message();
  for (const std::string& note : outcome->notes)
    EXPECT_THAT(note, ::testing::Not(HasSubstr("revolution")));
}

TEST(SymmetryNotesTest, NameTheAxisOrANearMiss) {
  SequenceAnnotation annotation;
  EXPECT_TRUE(SymmetryNotes(annotation, 0.001).empty());
  SymmetryCandidate near;
  near.symmetry.axis = Eigen::Vector3d::UnitY();
  near.displacement = 0.004;
  SymmetryCandidate far = near;
  far.displacement = 0.05;  // a gear's teeth: not worth a note
  annotation.symmetry_candidates = {near, far};
  const std::vector<std::string> notes = SymmetryNotes(annotation, 0.001);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_THAT(notes[0], HasSubstr("nearly a body of revolution about the axis (0.000, 1.000"));
  EXPECT_THAT(notes[0], HasSubstr("raise symmetry.tolerance above 0.004"));
  annotation.symmetry = RotationalSymmetry{Eigen::Vector3d::UnitX(), Eigen::Vector3d(1, 2, 3)};
  const std::vector<std::string> found = SymmetryNotes(annotation, 0.001);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_THAT(found[0], HasSubstr("body of revolution about the axis (1.000, 0.000, 0.000) through "
                                  "(1.00, 2.00, 3.00) mm"));
}

}  // namespace
}  // namespace bcot
