// Helpers of the capture tests: scripted frame sources and a check that a recorded sequence
// directory is valid (same frame count per camera, readable PNGs, one timestamp row per frame).
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "bcot/capture/frame_source.h"
#include "bcot/core/file_util.h"
#include "bcot/core/sequence.h"

namespace bcot::test {

// A source that replays a script: entry k is what the k-th Grab returns. Host stamps are
// set by the script; Trigger counts calls.
class ScriptedSource : public FrameSource {
 public:
  ScriptedSource(std::string name, std::vector<GrabResult> script)
      : name_(std::move(name)), script_(std::move(script)) {}
  const std::string& name() const override { return name_; }
  std::string description() const override { return "scripted source"; }
  Status Start() override {
    started_ = true;
    return Status::Ok();
  }
  Status Trigger() override {
    ++triggers_;
    return Status::Ok();
  }
  GrabResult Grab(int) override {
    if (next_ >= script_.size()) return {GrabStatus::kLost, Frame(), "end of script"};
    return script_[next_++];
  }
  void Stop() override { started_ = false; }
  int triggers() const { return triggers_; }

 private:
  std::string name_;
  std::vector<GrabResult> script_;
  size_t next_ = 0;
  int triggers_ = 0;
  bool started_ = false;
};

// A frame whose pixels encode (camera, index) and whose host stamp is `host_ns`.
inline GrabResult ScriptedFrame(int camera, int index, int64_t host_ns, int width = 32,
                                int height = 24) {
  GrabResult result;
  result.status = GrabStatus::kFrame;
  result.frame.image = cv::Mat(height, width, CV_8UC1, cv::Scalar(camera * 100 + index % 100));
  result.frame.host_timestamp_ns = host_ns;
  result.frame.device_timestamp_ns = 1000 + host_ns / 2;
  result.frame.frame_id = static_cast<uint64_t>(index);
  return result;
}

inline GrabResult Missed() { return {GrabStatus::kMissed, Frame(), "timeout"}; }

// Rows of timestamps.csv after the header, split at commas.
inline std::vector<std::vector<std::string>> ReadCsvRows(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  StatusOr<std::string> text = ReadTextFile(path);
  if (!text.ok()) return rows;
  const std::vector<std::string> lines = SplitLines(*text);
  for (size_t i = 1; i < lines.size(); ++i) rows.push_back(SplitTokens(lines[i], ","));
  return rows;
}

// Asserts the directory is a valid recording of `num_frames` frame sets of `cameras`.
inline void ExpectValidRecording(const std::string& dir, const std::vector<std::string>& cameras,
                                 int num_frames) {
  for (const std::string& camera : cameras) {
    const std::string folder = dir + "/" + camera;
    if (num_frames == 0) {
      EXPECT_FALSE(ListFrameImages(folder).ok()) << folder << " should hold no frames";
      continue;
    }
    StatusOr<std::vector<std::string>> frames = ListFrameImages(folder);
    ASSERT_TRUE(frames.ok()) << frames.status().message();
    EXPECT_EQ(static_cast<int>(frames->size()), num_frames) << folder;
    for (const std::string& frame : *frames) {
      EXPECT_FALSE(cv::imread(frame, cv::IMREAD_UNCHANGED).empty()) << frame;
    }
  }
  for (const char* csv : {"/timestamps.csv", "/device_timestamps.csv"}) {
    const auto rows = ReadCsvRows(dir + csv);
    ASSERT_EQ(static_cast<int>(rows.size()), num_frames) << csv;
    for (int i = 0; i < num_frames; ++i) {
      ASSERT_EQ(rows[i].size(), cameras.size() + 1) << csv << " row " << i;
      EXPECT_EQ(rows[i][0], std::to_string(i));
    }
  }
}

}  // namespace bcot::test
