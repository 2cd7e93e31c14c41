// The endpoints of `bcot review`'s server, through httplib's client, on a tiny synthetic
// sequence annotated with configs/track.yaml (and the same sequence without annotation).
#include "bcot/review/review_server.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "bcot/core/file_util.h"
#include "bcot/core/keyframes.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "synth_truth.h"
#include "test_util.h"

namespace bcot {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

constexpr int kFrames = 4;

// A ReviewServer on an ephemeral loopback port, answering on its own thread.
class RunningServer {
 public:
  explicit RunningServer(ReviewSession& session) {
    ReviewOptions options;
    options.port = 0;
    server_ = std::make_unique<ReviewServer>(session, options);
    const StatusOr<int> port = server_->Bind();
    BCOT_CHECK(port.ok());
    port_ = *port;
    server_->Start();
  }
  httplib::Client Client() const { return httplib::Client("127.0.0.1", port_); }
  const ReviewServer& server() const { return *server_; }

 private:
  std::unique_ptr<ReviewServer> server_;
  int port_ = 0;
};

class ReviewServerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    test::MakeTinyAnnotatedSequence(dir_->File("seq"), kFrames, dir_->File("ann"));
    annotated_ = ReviewSession::Load(dir_->File("seq"), dir_->File("ann"))->release();
    bare_ = ReviewSession::Load(dir_->File("seq"), "")->release();
  }
  static void TearDownTestSuite() {
    delete annotated_;
    delete bare_;
    delete dir_;
  }

  static json GetJson(httplib::Client& client, const std::string& path) {
    const httplib::Result result = client.Get(path);
    BCOT_CHECK(result && result->status == 200);
    EXPECT_EQ(result->get_header_value("Content-Type"), "application/json");
    return json::parse(result->body);
  }
  static cv::Mat GetImage(httplib::Client& client, const std::string& path) {
    const httplib::Result result = client.Get(path);
    BCOT_CHECK(result && result->status == 200);
    EXPECT_EQ(result->get_header_value("Content-Type"), "image/jpeg");
    const std::vector<unsigned char> bytes(result->body.begin(), result->body.end());
    return cv::imdecode(bytes, cv::IMREAD_COLOR);
  }

  static httplib::Result Post(httplib::Client& client, const std::string& path) {
    return client.Post(path, "", "");
  }
  // GET /api/job until its state is not "running" (at most 5 minutes).
  static json WaitForJob(httplib::Client& client) {
    json job;
    for (int attempt = 0; attempt < 3000; ++attempt) {
      job = GetJson(client, "/api/job");
      if (job["state"] != "running") break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return job;
  }
  // POST `path` is refused: 400 (or 404 for a frame outside the sequence) with `message`.
  static void ExpectRefused(httplib::Client& client, const std::string& path,
                            const std::string& message) {
    const httplib::Result answer = Post(client, path);
    ASSERT_TRUE(answer) << path;
    EXPECT_TRUE(answer->status == 400 || answer->status == 404) << path << ": " << answer->status;
    EXPECT_THAT(answer->body, HasSubstr(message)) << path;
  }
  static Eigen::Vector3d Translation(const json& pose) {
    return Eigen::Vector3d(pose["rig_from_object"][9], pose["rig_from_object"][10],
                           pose["rig_from_object"][11]);
  }

  static test::TempDir* dir_;
  static ReviewSession* annotated_;
  static ReviewSession* bare_;
};
test::TempDir* ReviewServerTest::dir_ = nullptr;
ReviewSession* ReviewServerTest::annotated_ = nullptr;
ReviewSession* ReviewServerTest::bare_ = nullptr;

TEST_F(ReviewServerTest, ServesTheEmbeddedPage) {
  RunningServer running(*annotated_);
  httplib::Client client = running.Client();
  const httplib::Result page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_THAT(page->get_header_value("Content-Type"), HasSubstr("text/html"));
  EXPECT_THAT(page->body, HasSubstr("<script src=\"review.js\">"));
  for (const char* asset : {"/review.js", "/review.css"}) {
    const httplib::Result result = client.Get(asset);
    ASSERT_TRUE(result) << asset;
    EXPECT_EQ(result->status, 200) << asset;
    EXPECT_FALSE(result->body.empty()) << asset;
  }
  EXPECT_THAT(running.server().Url(), HasSubstr("http://127.0.0.1:"));
}

TEST_F(ReviewServerTest, SequenceQualityAndDiagnosticsOfAnAnnotation) {
  RunningServer running(*annotated_);
  httplib::Client client = running.Client();
  const json sequence = GetJson(client, "/api/sequence");
  EXPECT_EQ(sequence["num_frames"], kFrames);
  EXPECT_EQ(sequence["annotation"], dir_->File("ann"));
  EXPECT_TRUE(sequence["contour"]);
  ASSERT_EQ(sequence["cameras"].size(), 2u);
  EXPECT_EQ(sequence["cameras"][0]["name"], "cam0");
  EXPECT_EQ(sequence["cameras"][1]["width"], 160);

  // The timeline repeats quality.json: per view the judged statistic and the bad frames.
  const json quality = GetJson(client, "/api/quality");
  const json stored = json::parse(*ReadTextFile(dir_->File("ann/quality.json")));
  EXPECT_TRUE(quality["available"]);
  EXPECT_EQ(quality["threshold_px"], stored["options"]["threshold_px"]);
  ASSERT_EQ(quality["views"].size(), stored["views"].size());
  const std::string key = stored["options"]["statistic"].get<std::string>() + "_px";
  std::vector<int> bad_frames;
  for (int f = 0; f < kFrames; ++f) {
    bool bad = false;
    for (size_t v = 0; v < stored["views"].size(); ++v) {
      EXPECT_EQ(quality["views"][v]["error_px"][f], stored["frames"][f]["views"][v][key]);
      bad = bad || stored["frames"][f]["views"][v]["bad"].get<bool>();
    }
    if (bad) bad_frames.push_back(f);
  }
  EXPECT_EQ(quality["bad_frames"].get<std::vector<int>>(), bad_frames);

  const json diagnostics = GetJson(client, "/api/frame/2/diagnostics");
  EXPECT_TRUE(diagnostics["available"]);
  EXPECT_EQ(diagnostics["values"]["frame"], "2");
  EXPECT_TRUE(diagnostics["values"].contains("termination"));
}

// The annotated image is the sequence's image with a green contour drawn on it; without an
// annotation it is the plain image.
TEST_F(ReviewServerTest, FrameImagesWithAndWithoutContour) {
  RunningServer with(*annotated_);
  RunningServer without(*bare_);
  httplib::Client client_with = with.Client();
  httplib::Client client_without = without.Client();
  for (const char* camera : {"cam0", "cam1"}) {
    const std::string path = std::string("/api/frame/1/view/") + camera + ".jpg";
    const cv::Mat contour = GetImage(client_with, path);
    const cv::Mat plain = GetImage(client_without, path);
    ASSERT_EQ(contour.size(), cv::Size(160, 128)) << camera;
    ASSERT_EQ(plain.size(), cv::Size(160, 128)) << camera;
    cv::Mat channels[3];
    cv::Mat difference;
    cv::absdiff(contour, plain, difference);
    cv::split(difference, channels);
    EXPECT_GT(cv::countNonZero(channels[1] > 60), 20) << camera << ": no contour drawn";
  }
  const json sequence = GetJson(client_without, "/api/sequence");
  EXPECT_FALSE(sequence["contour"]);
  EXPECT_TRUE(sequence["annotation"].is_null());
  EXPECT_FALSE(GetJson(client_without, "/api/quality")["available"]);
  EXPECT_FALSE(GetJson(client_without, "/api/frame/0/diagnostics")["available"]);
}

// The trajectory repeats rig_from_object.txt: the rotation from frame 0 and the position of the
// mesh's bounding-box centre in the rig, per frame; no keyframes in this sequence.
TEST_F(ReviewServerTest, TrajectoryOfTheAnnotation) {
  RunningServer with(*annotated_);
  RunningServer without(*bare_);
  httplib::Client client = with.Client();
  const json trajectory = GetJson(client, "/api/trajectory");
  ASSERT_TRUE(trajectory["available"]);
  ASSERT_EQ(trajectory["rotation_deg"].size(), static_cast<size_t>(kFrames));
  EXPECT_EQ(trajectory["rotation_deg"][0], 0.0);
  EXPECT_TRUE(trajectory["keyframes"].empty());
  const StatusOr<std::vector<Eigen::Isometry3d>> poses =
      ReadPoseFile(dir_->File("ann/rig_from_object.txt"));
  ASSERT_TRUE(poses.ok());
  const Eigen::Vector3d centre(trajectory["centre_mm"]["x"][2], trajectory["centre_mm"]["y"][2],
                               trajectory["centre_mm"]["z"][2]);
  // The centre moves with the pose: its offset from the pose's origin is the same rotated
  // vector in every frame.
  const Eigen::Vector3d in_object = (*poses)[2].inverse() * centre;
  for (int f = 0; f < kFrames; ++f) {
    const Eigen::Vector3d expected = (*poses)[f] * in_object;
    EXPECT_NEAR(trajectory["centre_mm"]["x"][f].get<double>(), expected.x(), 1e-6) << f;
    EXPECT_NEAR(trajectory["centre_mm"]["z"][f].get<double>(), expected.z(), 1e-6) << f;
    EXPECT_NEAR(trajectory["rotation_deg"][f].get<double>(),
                RotationDistanceDeg((*poses)[0].linear(), (*poses)[f].linear()), 1e-9)
        << f;
  }
  httplib::Client bare = without.Client();
  EXPECT_FALSE(GetJson(bare, "/api/trajectory")["available"]);
}

// ?mask=1 tints the silhouette green: the same image without it differs inside the object.
TEST_F(ReviewServerTest, MaskTintsTheSilhouette) {
  RunningServer running(*annotated_);
  httplib::Client client = running.Client();
  const cv::Mat plain = GetImage(client, "/api/frame/1/view/cam0.jpg");
  const cv::Mat masked = GetImage(client, "/api/frame/1/view/cam0.jpg?mask=1");
  ASSERT_EQ(plain.size(), masked.size());
  cv::Mat channels[3];
  cv::split(masked - plain, channels);  // saturating: where masked is greener / brighter
  EXPECT_GT(cv::countNonZero(channels[1] > 40), 200) << "no green tint";
  cv::split(plain - masked, channels);
  EXPECT_GT(cv::countNonZero(channels[2] > 20), 100) << "red not darkened";
}

// Nudges change the frame's pose (and its image: a yellow contour), refine solves it back, undo
// restores it, and a keyframe writes the pose to the sequence's keyframes.txt and names the
// command to re-annotate.
TEST_F(ReviewServerTest, NudgeRefineUndoAndKeyframe) {
  test::TempDir work;
  const std::string seq = test::CopyTree(dir_->File("seq"), work.File("seq"));
  StatusOr<std::unique_ptr<ReviewSession>> session = ReviewSession::Load(seq, dir_->File("ann"));
  ASSERT_TRUE(session.ok()) << session.status().message();
  RunningServer running(**session);
  httplib::Client client = running.Client();
  const json original = GetJson(client, "/api/frame/2/pose");
  EXPECT_EQ(original["edits"], 0);
  const cv::Mat before = GetImage(client, "/api/frame/2/view/cam0.jpg");

  const httplib::Result nudged = client.Post("/api/frame/2/nudge?camera=cam0&dx=4&rz=5", "", "");
  ASSERT_TRUE(nudged);
  ASSERT_EQ(nudged->status, 200) << nudged->body;
  const json moved = json::parse(nudged->body);
  EXPECT_EQ(moved["edits"], 1);
  EXPECT_NE(moved["rig_from_object"], original["rig_from_object"]);
  EXPECT_EQ(GetJson(client, "/api/frame/2/pose"), moved);
  EXPECT_EQ(GetJson(client, "/api/frame/1/pose")["edits"], 0);
  const cv::Mat after = GetImage(client, "/api/frame/2/view/cam0.jpg");
  cv::Mat channels[3];
  cv::split(after - before, channels);
  EXPECT_GT(cv::countNonZero(channels[2] > 80), 10) << "no yellow contour of the edit";

  const httplib::Result keyframe = client.Post("/api/frame/2/keyframe", "", "");
  ASSERT_TRUE(keyframe);
  ASSERT_EQ(keyframe->status, 200) << keyframe->body;
  const json written = json::parse(keyframe->body);
  EXPECT_EQ(written["path"], seq + "/keyframes.txt");
  EXPECT_THAT(written["command"].get<std::string>(),
              HasSubstr("--config " + dir_->File("ann") + "/config.resolved.yaml --frames "));
  const StatusOr<KeyframePoses> keyframes = ReadKeyframeFile(seq + "/keyframes.txt", kFrames);
  ASSERT_TRUE(keyframes.ok()) << keyframes.status().message();
  ASSERT_EQ(keyframes->count(2), 1u);
  EXPECT_NEAR(keyframes->at(2).translation().x(), moved["rig_from_object"][9].get<double>(), 1e-9);

  // Refine solves the frame from the nudged pose: it returns close to the annotated pose.
  const httplib::Result refined = client.Post("/api/frame/2/refine", "", "");
  ASSERT_TRUE(refined);
  ASSERT_EQ(refined->status, 200) << refined->body;
  const json solved = json::parse(refined->body);
  EXPECT_EQ(solved["edits"], 2);
  EXPECT_TRUE(solved.contains("termination"));
  const auto translation = [](const json& pose) {
    return Eigen::Vector3d(pose["rig_from_object"][9], pose["rig_from_object"][10],
                           pose["rig_from_object"][11]);
  };
  const double nudged_mm = (translation(moved) - translation(original)).norm();
  EXPECT_LT((translation(solved) - translation(original)).norm(), nudged_mm / 3.0);
  const httplib::Result back = client.Post("/api/frame/2/undo", "", "");
  ASSERT_TRUE(back && back->status == 200);

  const httplib::Result undone = client.Post("/api/frame/2/undo", "", "");
  ASSERT_TRUE(undone && undone->status == 200);
  EXPECT_EQ(json::parse(undone->body), original);
  const httplib::Result nothing = client.Post("/api/frame/2/undo", "", "");
  ASSERT_TRUE(nothing);
  EXPECT_EQ(nothing->status, 400);
  EXPECT_THAT(nothing->body, HasSubstr("frame 2 has no edit to undo"));

  for (const char* path :
       {"/api/frame/2/nudge?camera=cam9&dx=1", "/api/frame/2/nudge?camera=cam0&dx=x",
        "/api/frame/2/nudge?camera=cam0&dy=1e9", "/api/frame/9/nudge?camera=cam0"}) {
    const httplib::Result bad = client.Post(path, "", "");
    ASSERT_TRUE(bad) << path;
    EXPECT_NE(bad->status, 200) << path;
  }
  RunningServer bare(*bare_);
  httplib::Client bare_client = bare.Client();
  const httplib::Result no_annotation =
      bare_client.Post("/api/frame/0/nudge?camera=cam0&dx=1", "", "");
  ASSERT_TRUE(no_annotation);
  EXPECT_EQ(no_annotation->status, 400);
  EXPECT_THAT(no_annotation->body, HasSubstr("no annotation to edit"));
}

// Re-annotating frames from the page: a nudged frame set as keyframe, frames 1..2 re-annotated
// in the background; the page's annotation is then the new one (the edits of those frames
// dropped, the edit of frame 3 kept), the files are a finished annotation again.
TEST_F(ReviewServerTest, ReannotateRunsInTheBackgroundAndReloads) {
  test::TempDir work;
  const std::string seq = test::CopyTree(dir_->File("seq"), work.File("seq"));
  const std::string ann = test::CopyTree(dir_->File("ann"), work.File("ann"));
  StatusOr<std::unique_ptr<ReviewSession>> session = ReviewSession::Load(seq, ann);
  ASSERT_TRUE(session.ok()) << session.status().message();
  RunningServer running(**session);
  httplib::Client client = running.Client();
  EXPECT_EQ(GetJson(client, "/api/job")["state"], "idle");
  const json original = GetJson(client, "/api/frame/1/pose");
  ASSERT_EQ(Post(client, "/api/frame/1/nudge?camera=cam0&dx=5")->status, 200);
  ASSERT_EQ(Post(client, "/api/frame/1/keyframe")->status, 200);
  ASSERT_EQ(Post(client, "/api/frame/3/nudge?camera=cam0&dy=3")->status, 200);
  const json nudged = GetJson(client, "/api/frame/1/pose");

  const httplib::Result started = Post(client, "/api/reannotate?first=1&last=2");
  ASSERT_TRUE(started);
  ASSERT_EQ(started->status, 200) << started->body;
  EXPECT_EQ(json::parse(started->body)["job"], "re-annotate 1:2");
  const json job = WaitForJob(client);
  ASSERT_EQ(job["state"], "done") << job.dump();
  EXPECT_THAT(job["message"].get<std::string>(), HasSubstr("frames 1:2 re-annotated"));
  EXPECT_EQ(job["done"], job["total"]);
  EXPECT_TRUE(std::filesystem::exists(ann + "/DONE"));

  // Frame 1 was solved from its nudged keyframe back towards the annotated pose.
  const json solved = GetJson(client, "/api/frame/1/pose");
  EXPECT_EQ(solved["edits"], 0);
  EXPECT_LT((Translation(solved) - Translation(original)).norm(),
            (Translation(nudged) - Translation(original)).norm() / 3.0);
  EXPECT_EQ(GetJson(client, "/api/frame/3/pose")["edits"], 1);
  const StatusOr<std::vector<Eigen::Isometry3d>> written =
      ReadPoseFile(ann + "/rig_from_object.txt");
  ASSERT_TRUE(written.ok()) << written.status().message();
  EXPECT_NEAR((*written)[1].translation().x(), Translation(solved).x(), 1e-6);
  EXPECT_EQ(GetJson(client, "/api/trajectory")["keyframes"], json::array({1}));

  for (const auto& [path, message] : std::vector<std::pair<std::string, std::string>>{
           {"/api/reannotate?first=2&last=1", "re-annotate 2:1"},
           {"/api/reannotate?first=0&last=9", "9"},
           {"/api/reannotate?first=x&last=1", "x"}}) {
    ExpectRefused(client, path, message);
  }
  RunningServer bare(*bare_);
  httplib::Client bare_client = bare.Client();
  ExpectRefused(bare_client, "/api/reannotate?first=0&last=1", "no annotation");
}

// The initial pose from clicks on the object's centre at frame 0: candidates, their overlays,
// the chosen one saved as init_pose.txt (never over an existing one without overwrite); at
// another frame it becomes that frame's keyframe.
TEST_F(ReviewServerTest, InitialPoseFromClicksIsSearchedDrawnAndSaved) {
  test::TempDir work;
  const std::string seq = test::CopyTree(dir_->File("seq"), work.File("seq"));
  std::filesystem::remove(seq + "/init_pose.txt");
  StatusOr<InitOptions> options = ReadInitOptions("", {"init.grid_rotations=1000"});
  ASSERT_TRUE(options.ok()) << options.status().message();
  StatusOr<std::unique_ptr<ReviewSession>> session = ReviewSession::Load(seq, "", *options);
  ASSERT_TRUE(session.ok()) << session.status().message();
  RunningServer running(**session);
  httplib::Client client = running.Client();
  EXPECT_EQ(GetJson(client, "/api/init")["candidates"], json::array());
  EXPECT_FALSE(GetJson(client, "/api/sequence")["init_pose"]);
  const auto click = [&](int camera, int frame) {
    const Eigen::Vector2d pixel = test::TrueCentrePixel(seq, camera, frame);
    return fmt::format("click=cam{}:{:.2f},{:.2f}", camera, pixel.x(), pixel.y());
  };

  for (const auto& [path, message] : std::vector<std::pair<std::string, std::string>>{
           {"/api/init?click=cam0:5", "expected CAM:X,Y"},
           {"/api/init?click=cam7:5,5", "cam7"},
           {"/api/init?frame=9&" + click(0, 0), "9"},
           {"/api/init", "click"}}) {
    ExpectRefused(client, path, message);
  }

  const httplib::Result started = Post(client, "/api/init?" + click(0, 0) + "&" + click(1, 0));
  ASSERT_TRUE(started);
  ASSERT_EQ(started->status, 200) << started->body;
  const json job = WaitForJob(client);
  ASSERT_EQ(job["state"], "done") << job.dump();
  const json init = GetJson(client, "/api/init");
  EXPECT_EQ(init["frame"], 0);
  ASSERT_GE(init["candidates"].size(), 1u);
  // The candidate's contour is drawn over the plain image.
  const cv::Mat plain = GetImage(client, "/api/frame/0/view/cam0.jpg");
  const cv::Mat drawn = GetImage(client, "/api/frame/0/view/cam0.jpg?candidate=0");
  cv::Mat change;
  cv::absdiff(plain, drawn, change);
  cv::Mat largest_change;
  cv::reduce(change.reshape(1, change.total()), largest_change, 1, cv::REDUCE_MAX);
  EXPECT_GT(cv::countNonZero(largest_change > 60), 40) << "no contour of the candidate";
  const httplib::Result unknown = client.Get("/api/frame/0/view/cam0.jpg?candidate=99");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 400);

  const httplib::Result saved = Post(client, "/api/init/save?candidate=0");
  ASSERT_TRUE(saved);
  ASSERT_EQ(saved->status, 200) << saved->body;
  EXPECT_EQ(json::parse(saved->body)["path"], seq + "/init_pose.txt");
  const StatusOr<std::vector<Eigen::Isometry3d>> pose = ReadPoseFile(seq + "/init_pose.txt");
  ASSERT_TRUE(pose.ok()) << pose.status().message();
  EXPECT_THAT(pose->front(), test::PoseNear(test::TruePose(seq, 0), 5.0, 10.0));
  EXPECT_TRUE(GetJson(client, "/api/sequence")["init_pose"]);
  ExpectRefused(client, "/api/init/save?candidate=0", "init_pose.txt exists");
  EXPECT_EQ(Post(client, "/api/init/save?candidate=0&overwrite=1")->status, 200);
  EXPECT_EQ(Post(client, "/api/init/save?candidate=99")->status, 400);

  // At frame 2 the pose becomes keyframe 2.
  ASSERT_EQ(Post(client, "/api/init?frame=2&" + click(0, 2) + "&" + click(1, 2))->status, 200);
  ASSERT_EQ(WaitForJob(client)["state"], "done");
  const httplib::Result keyframe = Post(client, "/api/init/save?candidate=0");
  ASSERT_TRUE(keyframe);
  ASSERT_EQ(keyframe->status, 200) << keyframe->body;
  EXPECT_EQ(json::parse(keyframe->body)["path"], seq + "/keyframes.txt");
  const StatusOr<KeyframePoses> keyframes = ReadKeyframeFile(seq + "/keyframes.txt", kFrames);
  ASSERT_TRUE(keyframes.ok()) << keyframes.status().message();
  EXPECT_EQ(keyframes->count(2), 1u);
}

// A new --annotation directory: "annotate" writes the annotation there in the background, and
// the server then serves it as if it had been given at start; without an anchor the job fails
// with annotate's own error, without a directory or with an annotation shown it is refused.
TEST_F(ReviewServerTest, AnnotateIntoTheGivenDirectoryThenShowIt) {
  test::TempDir work;
  const std::string seq = test::CopyTree(dir_->File("seq"), work.File("seq"));
  ASSERT_TRUE(ReadTextFile(seq + "/init_pose.txt").ok());
  std::filesystem::rename(seq + "/init_pose.txt", work.File("init_pose.txt"));
  StatusOr<std::unique_ptr<ReviewSession>> session = ReviewSession::Load(seq, work.File("new_ann"));
  ASSERT_TRUE(session.ok()) << session.status().message();
  RunningServer running(**session);
  httplib::Client client = running.Client();
  // A folder that is neither an annotation nor empty is refused.
  const StatusOr<std::unique_ptr<ReviewSession>> foreign = ReviewSession::Load(seq, seq + "/cam0");
  ASSERT_FALSE(foreign.ok());
  EXPECT_THAT(foreign.status().message(), HasSubstr("neither an annotation"));
  const json before = GetJson(client, "/api/sequence");
  EXPECT_FALSE(before["contour"]);
  EXPECT_EQ(before["annotation_target"], work.File("new_ann"));

  ASSERT_EQ(Post(client, "/api/annotate")->status, 200);
  const json failed = WaitForJob(client);
  EXPECT_EQ(failed["state"], "failed");
  EXPECT_THAT(failed["message"].get<std::string>(), HasSubstr("init_pose.txt"));

  std::filesystem::rename(work.File("init_pose.txt"), seq + "/init_pose.txt");
  ASSERT_EQ(Post(client, "/api/annotate")->status, 200);
  const json done = WaitForJob(client);
  ASSERT_EQ(done["state"], "done") << done.dump();
  EXPECT_THAT(done["message"].get<std::string>(),
              HasSubstr("annotated 4 frames into " + work.File("new_ann")));
  EXPECT_TRUE(std::filesystem::exists(work.File("new_ann/DONE")));
  const json after = GetJson(client, "/api/sequence");
  EXPECT_TRUE(after["contour"]);
  EXPECT_EQ(after["annotation"], work.File("new_ann"));
  EXPECT_TRUE(after["annotation_target"].is_null());
  EXPECT_TRUE(GetJson(client, "/api/quality")["available"]);
  EXPECT_EQ(GetJson(client, "/api/frame/0/pose")["edits"], 0);

  ExpectRefused(client, "/api/annotate", "shown already");
  RunningServer bare(*bare_);
  httplib::Client bare_client = bare.Client();
  ExpectRefused(bare_client, "/api/annotate", "--annotation DIR");
}

// Frames and cameras come from the sequence; anything else, path-like or not, is an error
// status and never a file of the disk.
TEST_F(ReviewServerTest, RejectsBadFramesCamerasAndPaths) {
  RunningServer running(*annotated_);
  httplib::Client client = running.Client();
  const std::vector<std::pair<std::string, int>> requests = {
      {"/api/frame/4/view/cam0.jpg", 404},
      {"/api/frame/99999/diagnostics", 404},
      {"/api/frame/-1/view/cam0.jpg", 400},
      {"/api/frame/x/view/cam0.jpg", 400},
      {"/api/frame/1e0/diagnostics", 400},
      {"/api/frame/0/view/cam9.jpg", 404},
      {"/api/frame/0/view/..%2Frig.yaml.jpg", 404},
      {"/api/frame/0/view/%2e%2e.jpg", 404},
      {"/api/frame/0/view/../../rig.yaml", 404},
      {"/rig.yaml", 404},
      {"/cam0/000000.png", 404},
      {"/index.html/../rig.yaml", 404},
      {"/review.js/..", 404},
  };
  for (const auto& [path, status] : requests) {
    const httplib::Result result = client.Get(path);
    ASSERT_TRUE(result) << path;
    EXPECT_EQ(result->status, status) << path << ": " << result->body;
    EXPECT_THAT(result->body, ::testing::Not(HasSubstr("cameras:"))) << path;
  }
  const httplib::Result camera = client.Get("/api/frame/0/view/cam9.jpg");
  EXPECT_THAT(camera->body, HasSubstr("cam0, cam1"));
}

}  // namespace
}  // namespace bcot
