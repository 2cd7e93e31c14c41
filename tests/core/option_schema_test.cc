#include "bcot/core/option_schema.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

enum class Mode { kFast, kSlow };

struct ToyOptions {
  int seed = 1;
  struct Solve {
    int rounds = 5;
    double tolerance_mm = 0.001;
    Mode mode = Mode::kFast;
    std::optional<Mode> refine_mode;
    bool verbose = false;
  } solve;
  struct View {
    std::vector<std::string> cameras;
    std::array<double, 3> sigma = {1.0, 2.0, 3.0};
    double scale = 1.0;
    double max_scale = 4.0;
    std::string mesh;
  } view;
};

const OptionSchema<ToyOptions>& ToySchema() {
  static const OptionSchema<ToyOptions>* const schema = [] {
    auto* s = new OptionSchema<ToyOptions>();
    s->Add(
         "seed", [](auto& o) -> auto& { return o.seed; }, "", "random seed")
        .Range(NonNegative());
    s->Add(
         "solve.rounds", [](auto& o) -> auto& { return o.solve.rounds; }, "", "rounds")
        .Range(AtLeast(1));
    s->Add(
         "solve.tolerance_mm", [](auto& o) -> auto& { return o.solve.tolerance_mm; }, "mm",
         "stop below this")
        .Range(NonNegative());
    s->AddChoice(
        "solve.mode", [](auto& o) -> auto& { return o.solve.mode; },
        std::vector<std::pair<std::string, Mode>>{{"fast", Mode::kFast}, {"slow", Mode::kSlow}},
        "how");
    s->AddChoice(
        "solve.refine_mode", [](auto& o) -> auto& { return o.solve.refine_mode; },
        std::vector<std::pair<std::string, std::optional<Mode>>>{
            {"same", std::nullopt}, {"fast", Mode::kFast}, {"slow", Mode::kSlow}},
        "refinement");
    s->Add(
        "solve.verbose", [](auto& o) -> auto& { return o.solve.verbose; }, "", "talk");
    s->Add(
        "view.cameras", [](auto& o) -> auto& { return o.view.cameras; }, "", "names");
    s->Add(
         "view.sigma", [](auto& o) -> auto& { return o.view.sigma; }, "deg", "per axis")
        .Range(Positive())
        .Elements({"x", "y", "z"});
    s->Add(
         "view.scale", [](auto& o) -> auto& { return o.view.scale; }, "px", "scale")
        .Range(Positive());
    s->Add(
         "view.max_scale", [](auto& o) -> auto& { return o.view.max_scale; }, "px", "largest")
        .Check([](const ToyOptions& o) {
          return o.view.max_scale > o.view.scale ? "" : "must be > view.scale";
        });
    s->Add(
         "view.mesh", [](auto& o) -> auto& { return o.view.mesh; }, "", "mesh file")
        .Path();
    return s;
  }();
  return *schema;
}

StatusOr<ToyOptions> Parse(const std::string& text, OptionSources* sources = nullptr) {
  ToyOptions options;
  OptionSources own;
  OptionSources* s = sources != nullptr ? sources : &own;
  BCOT_RETURN_IF_ERROR(ToySchema().Parse(YAML::Load(text), "run.yaml", "base", &options, s));
  BCOT_RETURN_IF_ERROR(ToySchema().Validate(options, s));
  return options;
}

TEST(OptionSchemaTest, ParsesEveryTypeAndRecordsSources) {
  OptionSources sources;
  const StatusOr<ToyOptions> options = Parse(
      "seed: 3\nsolve:\n  rounds: 2\n  mode: slow\n  refine_mode: same\n  verbose: true\n"
      "view:\n  cameras: [a, \"no\"]\n  sigma: [1, 1, 0.5]\n  mesh: m.obj\n",
      &sources);
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->seed, 3);
  EXPECT_EQ(options->solve.rounds, 2);
  EXPECT_EQ(options->solve.mode, Mode::kSlow);
  EXPECT_FALSE(options->solve.refine_mode.has_value());
  EXPECT_TRUE(options->solve.verbose);
  EXPECT_EQ(options->view.cameras, (std::vector<std::string>{"a", "no"}));
  EXPECT_DOUBLE_EQ(options->view.sigma[2], 0.5);
  EXPECT_EQ(options->view.mesh, "base/m.obj");
  EXPECT_EQ(sources.at("solve.rounds"), "run.yaml:3");
  EXPECT_EQ(sources.count("solve.tolerance_mm"), 0u);
}

TEST(OptionSchemaTest, UnknownKeyListsEveryKnownKeyOfItsLevel) {
  const Status top = Parse("solve:\n  rounds: 2\nsolver: 1\n").status();
  EXPECT_THAT(top.message(), HasSubstr("run.yaml:3: solver: unknown key"));
  EXPECT_THAT(top.message(), HasSubstr("did you mean 'solve'?"));
  // Every section, not only those present in the file.
  EXPECT_THAT(top.message(), HasSubstr("known keys: seed, solve, view"));
  const Status inner = Parse("solve:\n  roundz: 2\n").status();
  EXPECT_THAT(inner.message(),
              HasSubstr("run.yaml:2: solve.roundz: unknown key (did you mean 'rounds'?); known "
                        "keys: mode, refine_mode, rounds, tolerance_mm, verbose"));
}

TEST(OptionSchemaTest, TypeAndChoiceErrorsNameFileLineAndKey) {
  EXPECT_THAT(Parse("solve:\n  rounds: abc\n").status().message(),
              HasSubstr("run.yaml:2: solve.rounds: expected an integer, got 'abc'"));
  EXPECT_THAT(Parse("solve:\n  mode: medium\n").status().message(),
              HasSubstr("run.yaml:2: solve.mode: 'medium' is not one of fast | slow"));
  EXPECT_THAT(Parse("view:\n  sigma: [1, 2]\n").status().message(),
              HasSubstr("run.yaml:2: view.sigma: has 2 values, expected 3 (x, y, z)"));
}

TEST(OptionSchemaTest, RangeViolationsNameFileLineAndKey) {
  const Status status = Parse(
                            "solve:\n  tolerance_mm: 1\n  rounds: 0\nview:\n  sigma: [1, 0, 1]\n"
                            "  scale: 5\n")
                            .status();
  test::ExpectErrorNaming(
      status, StatusCode::kInvalidConfig,
      {"run.yaml:3: solve.rounds = 0, must be >= 1", "run.yaml:5: view.sigma = 0 (y), must be > 0",
       // A rule across fields, attached to a key that kept its default.
       "view.max_scale = 4 (default), must be > view.scale"});
}

TEST(OptionSchemaTest, OverridesNameSetInEveryError) {
  const OptionSchema<ToyOptions>& schema = ToySchema();
  test::TempDir dir;
  test::WriteText(dir.File("run.yaml"), "solve:\n  rounds: 2\n");
  const std::string path = dir.File("run.yaml");
  const StatusOr<ToyOptions> type = schema.Read(path, {"solve.rounds=abc"});
  EXPECT_EQ(type.status().message(), "--set solve.rounds: expected an integer, got 'abc'");
  const StatusOr<ToyOptions> range = schema.Read(path, {"solve.rounds=0"});
  EXPECT_EQ(range.status().message(), "--set solve.rounds = 0, must be >= 1");
  const StatusOr<ToyOptions> key = schema.Read(path, {"solve.roundz=2"});
  EXPECT_THAT(key.status().message(), HasSubstr("--set solve.roundz: unknown key"));
  EXPECT_THAT(key.status().message(), Not(HasSubstr("run.yaml")));
  OptionSources sources;
  const StatusOr<ToyOptions> good = schema.Read(path, {"solve.mode=slow"}, &sources);
  ASSERT_TRUE(good.ok()) << good.status().message();
  EXPECT_EQ(good->solve.rounds, 2);
  EXPECT_EQ(good->solve.mode, Mode::kSlow);
  EXPECT_EQ(sources.at("solve.rounds"), path + ":2");
  EXPECT_EQ(sources.at("solve.mode"), "--set");
}

TEST(OptionSchemaTest, EmittedYamlReadsBackIdentically) {
  ToyOptions options;
  options.seed = 7;
  options.solve.tolerance_mm = 0.1;
  options.solve.refine_mode = Mode::kSlow;
  options.view.cameras = {"left", "no", "1.5", ""};
  options.view.sigma = {0.25, 1e-7, 3};
  options.view.mesh = "/abs/path with space.obj";
  const std::string text = ToySchema().Emit(options, {"resolved options"});
  EXPECT_THAT(text, HasSubstr("# resolved options\n"));
  EXPECT_THAT(text, HasSubstr("  tolerance_mm: 0.1\n"));
  ToyOptions read;
  ASSERT_TRUE(ToySchema().Parse(YAML::Load(text), "emitted", "", &read, nullptr).ok()) << text;
  EXPECT_EQ(ToySchema().Emit(read, {"resolved options"}), text);
  EXPECT_EQ(read.view.cameras, options.view.cameras);
  EXPECT_EQ(read.solve.refine_mode, options.solve.refine_mode);
  EXPECT_EQ(read.view.sigma, options.view.sigma);
  EXPECT_EQ(read.view.mesh, options.view.mesh);
}

TEST(OptionSchemaTest, HelpListsEveryKeyWithDefaultUnitAndRule) {
  const std::string help = ToySchema().Help();
  EXPECT_THAT(help, HasSubstr("solve.rounds = 5"));
  EXPECT_THAT(help, HasSubstr("(>= 1) rounds"));
  EXPECT_THAT(help, HasSubstr("solve.tolerance_mm = 0.001 mm"));
  EXPECT_THAT(help, HasSubstr("(fast | slow) how"));
  EXPECT_THAT(help, HasSubstr("view.sigma = [1, 2, 3] deg"));
  EXPECT_EQ(ToySchema().Example(), "seed=1");
  for (const auto& option : ToySchema().options()) {
    EXPECT_THAT(help, HasSubstr(option->info().key + " = "));
  }
}

// A custom option: a list of {name, size} mappings with its own reader and writer; its part
// rules are located at the option's key and listed with the others.
struct Part {
  std::string name;
  int size = 0;
};
struct PartsOptions {
  std::vector<Part> parts;
};

const OptionSchema<PartsOptions>& PartsSchema() {
  static const OptionSchema<PartsOptions>* const schema = [] {
    auto* s = new OptionSchema<PartsOptions>();
    const auto read = [](YamlMap& map, const std::string&, std::vector<Part>* parts) -> Status {
      const YAML::Node node = map.Node("parts");
      if (!node.IsSequence()) return map.Error("parts", "expected a list");
      parts->clear();
      for (size_t i = 0; i < node.size(); ++i) {
        YamlMap item(node[i], map.source_name(), "parts[" + std::to_string(i) + "]",
                     StatusCode::kInvalidConfig);
        Part part;
        BCOT_RETURN_IF_ERROR(item.Get("name", &part.name));
        BCOT_RETURN_IF_ERROR(item.Get("size", &part.size));
        BCOT_RETURN_IF_ERROR(item.CheckNoUnknownKeys());
        parts->push_back(part);
      }
      return Status::Ok();
    };
    const auto emit = [](YAML::Emitter& out, const std::vector<Part>& parts) {
      out << YAML::Flow << YAML::BeginSeq;
      for (const Part& part : parts) {
        out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << part.name << YAML::Key
            << "size" << YAML::Value << part.size << YAML::EndMap;
      }
      out << YAML::EndSeq;
    };
    const auto text = [](const std::vector<Part>& parts) {
      return std::to_string(parts.size()) + " parts";
    };
    s->AddCustom(
         "parts", [](auto& o) -> auto& { return o.parts; }, read, emit, text, "the parts")
        .Check([](const PartsOptions& o) { return o.parts.empty() ? "must not be empty" : ""; })
        .CheckParts([](const PartsOptions& o) {
          std::vector<option_internal::PartViolation> violations;
          for (size_t i = 0; i < o.parts.size(); ++i) {
            if (o.parts[i].size <= 0) {
              violations.push_back({"parts[" + std::to_string(i) + "].size",
                                    std::to_string(o.parts[i].size), "must be > 0"});
            }
          }
          return violations;
        });
    return s;
  }();
  return *schema;
}

TEST(OptionSchemaTest, CustomOptionsReadEmitAndCheckTheirParts) {
  const OptionSchema<PartsOptions>& schema = PartsSchema();
  PartsOptions options;
  OptionSources sources;
  ASSERT_TRUE(schema
                  .Parse(YAML::Load("parts:\n  - {name: a, size: 2}\n  - {name: b, size: 0}\n"),
                         "run.yaml", "", &options, &sources)
                  .ok());
  ASSERT_EQ(options.parts.size(), 2u);
  EXPECT_EQ(options.parts[1].name, "b");
  const Status invalid = schema.Validate(options, &sources);
  ASSERT_FALSE(invalid.ok());
  EXPECT_EQ(invalid.message(), "run.yaml:1: parts[1].size = 0, must be > 0");

  // Unknown keys inside the list, a wrong type, and --set name their place.
  PartsOptions other;
  const Status unknown =
      schema.Parse(YAML::Load("parts:\n  - {name: a, size: 2, colour: red}\n"), "run.yaml", "", &other, nullptr);
  EXPECT_THAT(unknown.message(), HasSubstr("run.yaml:2: parts[0].colour: unknown key"));
  const Status scalar = schema.ApplyOverrides({"parts=3"}, &other, nullptr);
  EXPECT_THAT(scalar.message(), HasSubstr("--set parts: expected a list"));

  // Emitted, it reads back the same; empty, the whole-option rule fires.
  options.parts[1].size = 4;
  const std::string emitted = schema.Emit(options);
  PartsOptions read;
  ASSERT_TRUE(schema.Parse(YAML::Load(emitted), "emitted", "", &read, nullptr).ok()) << emitted;
  EXPECT_EQ(schema.Emit(read), emitted);
  EXPECT_TRUE(schema.Validate(read, nullptr).ok());
  EXPECT_EQ(schema.Validate(PartsOptions(), nullptr).message(),
            "parts = 0 parts, must not be empty");
  EXPECT_THAT(schema.Help(), HasSubstr("parts = 0 parts"));
}

}  // namespace
}  // namespace bcot
