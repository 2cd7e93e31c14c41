// Every file under configs/ is read by the reader of the command it belongs to.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/file_util.h"
#include "bcot/eval/evaluator.h"
#include "bcot/export/exporter.h"
#include "bcot/synth/synth_options.h"
#include "test_util.h"

namespace bcot {
namespace {

TEST(ConfigFilesTest, EveryFileInConfigsLoadsWithItsReader) {
  int loaded = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(test::SourcePath("configs"))) {
    if (!entry.is_regular_file()) continue;
    const std::string path = entry.path().string();
    const std::string name = entry.path().filename().string();
    const std::string parent = entry.path().parent_path().filename().string();
    Status status;
    if (name == "annotate.yaml" || name == "track.yaml") {
      status = ReadAnnotateOptions(path, {}).status();
    } else if (name == "eval.yaml") {
      status = ReadEvalOptions(path).status();
    } else if (name == "export.yaml") {
      status = ReadExportOptions(path).status();
    } else if (parent == "synth") {
      status = ReadSynthOptions(path).status();
    } else if (name == "capture.yaml" || name == "calibrate.yaml") {
      continue;
    } else if (parent == "pbr" && entry.path().extension() == ".json") {
      // Scene specs of the Blender render path (scripts/pbr reads them): a JSON object.
      const StatusOr<std::string> text = ReadTextFile(path);
      const nlohmann::json json =
          text.ok() ? nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false)
                    : nlohmann::json();
      status = json.is_object() ? Status::Ok() : Status::InvalidInput("not a JSON object");
    } else {
      ADD_FAILURE() << path << ": no reader known to this test";
      continue;
    }
    EXPECT_TRUE(status.ok()) << path << ": " << status.message();
    ++loaded;
  }
  EXPECT_GE(loaded, 10);
}

}  // namespace
}  // namespace bcot
