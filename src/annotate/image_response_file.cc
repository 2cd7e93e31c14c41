#include "bcot/annotate/image_response_file.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <exception>
#include <limits>

#include "bcot/core/file_util.h"
#include "bcot/core/yaml_util.h"

namespace bcot {
namespace {

// The written name of a resolved response kind.
const char* KindName(ImageResponse::Kind kind) {
  switch (kind) {
    case ImageResponse::Kind::kGamma:
      return "gamma";
    case ImageResponse::Kind::kTable:
      return "table";
    case ImageResponse::Kind::kLog:
      return "log";
    case ImageResponse::Kind::kSrgb:
    case ImageResponse::Kind::kAuto:
      break;
  }
  return "srgb";
}

// A response as Name() writes it ("srgb", "gamma 1.8", "log 10"); `where` locates it in
// messages.
StatusOr<ImageResponse> ResponseFromName(const std::string& name, const std::string& where) {
  if (name == "srgb") return ImageResponse();
  // "<kind> <number>": the number after the prefix, the whole rest of the name.
  const auto number_after = [&name](const std::string& prefix, double* value) {
    if (name.rfind(prefix, 0) != 0) return false;
    size_t used = 0;
    try {
      *value = std::stod(name.substr(prefix.size()), &used);
    } catch (const std::exception&) {
      return false;
    }
    return used > 0 && prefix.size() + used == name.size();
  };
  ImageResponse response;
  double value = 0.0;
  if (number_after("gamma ", &value)) response = ImageResponse::Gamma(value);
  if (number_after("log ", &value)) response = ImageResponse::Log(value);
  if (response.kind == ImageResponse::Kind::kSrgb || !response.IsValid()) {
    return Status::InvalidInput(
        fmt::format("{}: '{}' is not a response (srgb, gamma G with G in [{}, {}], or log S with "
                    "S in [{}, {}])",
                    where, name, ImageResponse::kMinGamma, ImageResponse::kMaxGamma,
                    ImageResponse::kMinLogStops, ImageResponse::kMaxLogStops));
  }
  return response;
}

// The response of the file's `response` (srgb | gamma | table | log), `gamma`, `table_file`
// and `log_stops` keys.
StatusOr<ImageResponse> ParseResponse(YamlMap* map) {
  int kind = -1;
  BCOT_RETURN_IF_ERROR(
      map->GetOptionalChoice("response", {"srgb", "gamma", "table", "log"}, &kind));
  if (kind < 0) return map->Error("response", "missing (srgb | gamma | table | log)");
  ImageResponse response;
  if (kind == 2) {
    response.kind = ImageResponse::Kind::kTable;
    BCOT_RETURN_IF_ERROR(map->Get("table_file", &response.table_file));
    StatusOr<std::vector<float>> table = ReadResponseTable(response.table_file);
    if (!table.ok()) return map->Error("table_file", table.status().message());
    response.table = std::move(table).value();
  }
  if (kind == 1) {
    response.kind = ImageResponse::Kind::kGamma;
    BCOT_RETURN_IF_ERROR(map->Get("gamma", &response.gamma));
    if (!response.IsValid()) {
      return map->Error("gamma", fmt::format("{} is outside [{}, {}]", response.gamma,
                                             ImageResponse::kMinGamma, ImageResponse::kMaxGamma));
    }
  }
  if (kind == 3) {
    response.kind = ImageResponse::Kind::kLog;
    BCOT_RETURN_IF_ERROR(map->Get("log_stops", &response.log_stops));
    if (!response.IsValid()) {
      return map->Error("log_stops",
                        fmt::format("{} is outside [{}, {}]", response.log_stops,
                                    ImageResponse::kMinLogStops, ImageResponse::kMaxLogStops));
    }
  }
  return response;
}

}  // namespace

std::string FormatImageResponseRecord(const ImageResponseRecord& record) {
  BCOT_CHECK(record.response.IsResolved());
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "response" << YAML::Value << KindName(record.response.kind);
  if (record.response.kind == ImageResponse::Kind::kGamma) {
    out << YAML::Key << "gamma" << YAML::Value << record.response.gamma;
  }
  if (record.response.kind == ImageResponse::Kind::kLog) {
    out << YAML::Key << "log_stops" << YAML::Value << record.response.log_stops;
  }
  if (record.response.kind == ImageResponse::Kind::kTable) {
    out << YAML::Key << "table_file" << YAML::Value << record.response.table_file;
  }
  out << YAML::Key << "estimated" << YAML::Value << record.estimated;
  if (!record.estimate_error.empty()) {
    out << YAML::Key << "estimate_error" << YAML::Value << record.estimate_error;
  }
  if (!record.scores.empty()) {
    out << YAML::Key << "candidates" << YAML::Value << YAML::BeginSeq;
    for (const ResponseScore& score : record.scores) {
      out << YAML::Flow << YAML::BeginMap;
      out << YAML::Key << "response" << YAML::Value << score.response.Name();
      for (const auto& [key, value] :
           {std::pair{"slope_px", score.slope_px},
            std::pair{"slope_standard_error_px", score.slope_standard_error_px},
            std::pair{"spread_px", score.spread_px},
            std::pair{"spread_standard_error_px", score.spread_standard_error_px}}) {
        out << YAML::Key << key << YAML::Value;
        if (std::isfinite(value)) {
          out << fmt::format("{:.4f}", value);
        } else {
          out << YAML::Null;  // the candidate failed
        }
      }
      out << YAML::Key << "lines" << YAML::Value << score.lines;
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  return fmt::format(
      "# bcot annotate: the cameras' response the edges were decoded with (edge.response);\n"
      "# candidates, at the first frame's pose: the polarity slope of the edges (px; how far they\n"
      "# sit towards their bright side, 0 under the right response) and the spread of their\n"
      "# offsets (px), each with its standard error; the first is kept unless one of the two\n"
      "# clearly says otherwise (optim/response_estimation.h)\n{}\n",
      out.c_str());
}

Status WriteImageResponseFile(const std::string& annotation_dir,
                              const ImageResponseRecord& record) {
  return WriteFileAtomic(annotation_dir + "/" + kImageResponseFileName,
                         FormatImageResponseRecord(record));
}

StatusOr<ImageResponseRecord> ReadImageResponseFile(const std::string& annotation_dir) {
  const std::string path = annotation_dir + "/" + kImageResponseFileName;
  BCOT_ASSIGN_OR_RETURN(const YAML::Node root, LoadYamlFile(path));
  YamlMap map(root, path, "");
  ImageResponseRecord record;
  BCOT_ASSIGN_OR_RETURN(record.response, ParseResponse(&map));
  BCOT_RETURN_IF_ERROR(map.Get("estimated", &record.estimated));
  BCOT_RETURN_IF_ERROR(map.GetOptional("estimate_error", &record.estimate_error));
  if (map.Has("candidates")) {
    const YAML::Node candidates = map.Node("candidates");
    if (!candidates.IsSequence()) return map.Error("candidates", "must be a list");
    for (size_t i = 0; i < candidates.size(); ++i) {
      YamlMap entry(candidates[i], path, fmt::format("candidates[{}]", i));
      ResponseScore score;
      std::string name;
      BCOT_RETURN_IF_ERROR(entry.Get("response", &name));
      BCOT_ASSIGN_OR_RETURN(score.response, ResponseFromName(name, entry.Where("response")));
      for (const auto& [key, value] :
           {std::pair{"slope_px", &score.slope_px},
            std::pair{"slope_standard_error_px", &score.slope_standard_error_px},
            std::pair{"spread_px", &score.spread_px},
            std::pair{"spread_standard_error_px", &score.spread_standard_error_px}}) {
        if (entry.Has(key) && entry.Node(key).IsNull()) {
          *value = std::numeric_limits<double>::quiet_NaN();
        } else {
          BCOT_RETURN_IF_ERROR(entry.Get(key, value));
        }
      }
      BCOT_RETURN_IF_ERROR(entry.Get("lines", &score.lines));
      record.scores.push_back(score);
    }
  }
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  return record;
}

StatusOr<ImageResponseRecord> RecordedImageResponse(const std::string& annotation_dir,
                                                    const ImageResponse& configured) {
  if (configured.IsResolved()) {
    ImageResponseRecord record;
    record.response = configured;
    return record;
  }
  StatusOr<ImageResponseRecord> record = ReadImageResponseFile(annotation_dir);
  if (record.status().code() == StatusCode::kNotFound) {
    return Status::NotFound(fmt::format(
        "{} (edge.response is auto: the estimate the annotation used is recorded there; an "
        "annotation written without it decoded its images as sRGB: --set edge.response=srgb)",
        record.status().message()));
  }
  return record;
}

}  // namespace bcot
