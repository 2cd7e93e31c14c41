#include "bcot/core/yaml_util.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::StartsWith;

YAML::Node Parse(const std::string& text) {
  StatusOr<YAML::Node> node = ParseYaml(text, "cfg.yaml");
  EXPECT_TRUE(node.ok()) << node.status().message();
  return node.ok() ? *node : YAML::Node();
}

// The `region` section of `text`, read as cfg.yaml.
YamlMap RegionMap(const std::string& text) {
  const YAML::Node root = Parse(text);
  return YamlMap(root["region"], "cfg.yaml", "region");
}

// Line numbers in the tests below are 1-based lines of this text.
constexpr char kConfig[] =
    "name: demo\n"              // 1
    "region:\n"                 // 2
    "  band_px: 12\n"           // 3
    "  scale: 0.5\n"            // 4
    "  enabled: true\n"         // 5
    "  levels: [4, 2, 1]\n"     // 6
    "  weights: [0.5, 1e-3]\n"  // 7
    "  views: [cam0, cam1]\n"   // 8
    "  K: [1, 2,\n"             // 9
    "      3, oops]\n";         // 10

TEST(ParseYamlTest, SyntaxErrorNamesSourceAndLine) {
  const StatusOr<YAML::Node> node = ParseYaml("a: 1\n  b: 2\n", "cfg.yaml");
  ASSERT_FALSE(node.ok());
  EXPECT_EQ(node.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(node.status().message(), StartsWith("cfg.yaml:2: YAML syntax error"));
}

TEST(ParseYamlTest, SyntaxErrorUsesRequestedCode) {
  const StatusOr<YAML::Node> node =
      ParseYaml("a: [1, 2\nb: 3\n", "run.yaml", StatusCode::kInvalidConfig);
  ASSERT_FALSE(node.ok());
  EXPECT_EQ(node.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(node.status().message(), StartsWith("run.yaml:2: YAML syntax error"));
}

TEST(ParseYamlTest, SeveralDocumentsAreAnError) {
  const StatusOr<YAML::Node> node = ParseYaml("a: 1\n---\nb: 2\n", "cfg.yaml");
  ASSERT_FALSE(node.ok());
  EXPECT_THAT(node.status().message(),
              AllOf(StartsWith("cfg.yaml:2: "), HasSubstr("more than one YAML document")));
}

// yaml-cpp's parser returns the document of a lone ',' again and again without consuming
// input (YAML::LoadAll never returned on it and grew to gigabytes, found by the fuzz target of
// object.yaml): a syntax error now, in a file and in a --set value.
TEST(ParseYamlTest, InputThatStallsTheParserIsASyntaxError) {
  for (const char* text : {",", ",a", "  ,\n", ", x: 1"}) {
    const StatusOr<YAML::Node> node = ParseYaml(text, "object.yaml");
    ASSERT_FALSE(node.ok()) << text;
    EXPECT_THAT(node.status().message(), StartsWith("object.yaml:1: YAML syntax error")) << text;
  }
  YAML::Node root;
  const Status status = ApplyYamlOverrides({"frame.rounds=,"}, &root);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("frame.rounds"));
}

// Nested aliases ("billion laughs") and deep nesting are refused before any reader walks them.
TEST(ParseYamlTest, AliasBombsAndDeepNestingAreErrors) {
  std::string bomb = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i <= 9; ++i) {
    bomb += fmt::format(
        "a{0}: &a{0} [*a{1}, *a{1}, *a{1}, *a{1}, *a{1}, *a{1}, *a{1}, *a{1}, "
        "*a{1}, *a{1}]\n",
        i, i - 1);
  }
  const StatusOr<YAML::Node> exploded = ParseYaml(bomb, "cfg.yaml");
  ASSERT_FALSE(exploded.ok());
  EXPECT_EQ(exploded.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(exploded.status().message(), HasSubstr("cfg.yaml: more than 100000 YAML nodes"));
  const std::string deep = std::string(80, '[') + std::string(80, ']');
  const StatusOr<YAML::Node> nested = ParseYaml(deep, "cfg.yaml");
  ASSERT_FALSE(nested.ok());
  EXPECT_THAT(nested.status().message(), HasSubstr("nested deeper than 64 levels"));
  // An alias used a few times is fine.
  EXPECT_TRUE(ParseYaml("a: &k [1, 2]\nb: *k\nc: *k\n", "cfg.yaml").ok());
}

TEST(ParseYamlTest, EmptyTextIsNull) {
  const StatusOr<YAML::Node> node = ParseYaml("", "cfg.yaml");
  ASSERT_TRUE(node.ok());
  EXPECT_TRUE(node->IsNull());
  YamlMap map(*node, "cfg.yaml", "");
  EXPECT_TRUE(map.Check().ok());
  int value = 5;
  EXPECT_TRUE(map.GetOptional("x", &value).ok());
  EXPECT_EQ(value, 5);
}

TEST(LoadYamlFileTest, ReadsFileAndReportsMissingFile) {
  test::TempDir dir;
  test::WriteText(dir.File("a.yaml"), "x: 3\n");
  const StatusOr<YAML::Node> node = LoadYamlFile(dir.File("a.yaml"));
  ASSERT_TRUE(node.ok()) << node.status().message();
  EXPECT_EQ((*node)["x"].as<int>(), 3);

  const StatusOr<YAML::Node> missing = LoadYamlFile(dir.File("b.yaml"));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(missing.status().message(), HasSubstr("b.yaml"));
}

TEST(YamlWhereTest, OneBasedLineOrJustTheSource) {
  const YAML::Node root = Parse(kConfig);
  EXPECT_EQ(YamlWhere("cfg.yaml", root["region"]["scale"]), "cfg.yaml:4");
  EXPECT_EQ(YamlWhere("cfg.yaml", YAML::Node(3)), "cfg.yaml");
  EXPECT_EQ(YamlWhere("cfg.yaml", root["absent"]), "cfg.yaml");
}

TEST(YamlMapTest, ReadsEveryType) {
  const YAML::Node root = Parse(kConfig);
  YamlMap top(root, "cfg.yaml", "");
  std::string name;
  ASSERT_TRUE(top.Get("name", &name).ok());
  EXPECT_EQ(name, "demo");

  YamlMap region(top.Node("region"), "cfg.yaml", "region");
  int band_px = 0;
  double scale = 0.0;
  bool enabled = false;
  std::vector<int> levels;
  std::vector<double> weights;
  std::vector<std::string> views;
  ASSERT_TRUE(region.Get("band_px", &band_px).ok());
  ASSERT_TRUE(region.Get("scale", &scale).ok());
  ASSERT_TRUE(region.Get("enabled", &enabled).ok());
  ASSERT_TRUE(region.Get("levels", &levels).ok());
  ASSERT_TRUE(region.Get("weights", &weights).ok());
  ASSERT_TRUE(region.Get("views", &views).ok());
  EXPECT_EQ(band_px, 12);
  EXPECT_EQ(scale, 0.5);
  EXPECT_TRUE(enabled);
  EXPECT_THAT(levels, ElementsAre(4, 2, 1));
  EXPECT_THAT(weights, ElementsAre(0.5, 1e-3));
  EXPECT_THAT(views, ElementsAre("cam0", "cam1"));
  EXPECT_EQ(region.KeyPath("band_px"), "region.band_px");
  EXPECT_EQ(region.Where("band_px"), "cfg.yaml:3: region.band_px");
}

TEST(YamlMapTest, SequenceElementErrorPointsAtTheElementsLine) {
  YamlMap region = RegionMap(kConfig);
  std::vector<double> k;
  const Status status = region.Get("K", &k);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_EQ(status.message(), "cfg.yaml:10: region.K[3]: expected a number, got 'oops'");
}

TEST(YamlMapTest, MissingRequiredKeyNamesMapLineAndPath) {
  YamlMap region = RegionMap(kConfig);
  double value = 0.0;
  const Status status = region.Get("sigma", &value);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "cfg.yaml:3: region.sigma: missing required key");
}

TEST(YamlMapTest, GetOptionalChoiceMapsNamesAndListsTheChoices) {
  YamlMap map(Parse("kind: local\nform: fast\n"), "cfg.yaml", "");
  int kind = 0;
  ASSERT_TRUE(map.GetOptionalChoice("kind", {"global", "local"}, &kind).ok());
  EXPECT_EQ(kind, 1);
  int absent = 7;
  ASSERT_TRUE(map.GetOptionalChoice("mode", {"a", "b"}, &absent).ok());
  EXPECT_EQ(absent, 7);
  int form = 0;
  const Status bad = map.GetOptionalChoice("form", {"sqrt_energy", "irls"}, &form);
  EXPECT_THAT(bad.message(), HasSubstr("cfg.yaml:2"));
  EXPECT_THAT(bad.message(), HasSubstr("'fast' is not one of sqrt_energy | irls"));
  EXPECT_EQ(form, 0);
  EXPECT_TRUE(map.CheckNoUnknownKeys().ok());
}

TEST(YamlMapTest, GetOptionalKeepsDefaultWhenAbsentAndParsesWhenPresent) {
  YamlMap region = RegionMap(kConfig);
  double sigma = 1.25;
  ASSERT_TRUE(region.GetOptional("sigma", &sigma).ok());
  EXPECT_EQ(sigma, 1.25);
  int band_px = 0;
  ASSERT_TRUE(region.GetOptional("band_px", &band_px).ok());
  EXPECT_EQ(band_px, 12);
  bool enabled = false;
  ASSERT_TRUE(region.GetOptional("enabled", &enabled).ok());
  EXPECT_TRUE(enabled);
}

// Every case reads key `v` from a one-line document; the type is chosen by the test body.
TEST(YamlMapTest, WrongTypesNameLineKeyValueAndExpectation) {
  const auto check = [](const Status& status, const std::string& expected) {
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
    EXPECT_EQ(status.message(), expected);
  };
  const auto map = [](const std::string& text) {
    return YamlMap(Parse("# comment\n" + text), "cfg.yaml", "sec");
  };
  int i = 0;
  double d = 0.0;
  bool b = false;
  std::string s;
  std::vector<int> vi;
  std::vector<double> vd;
  check(map("v: 1.5").Get("v", &i), "cfg.yaml:2: sec.v: expected an integer, got '1.5'");
  check(map("v: 3000000000").Get("v", &i),
        "cfg.yaml:2: sec.v: expected an integer in [-2147483648, 2147483647], got '3000000000'");
  check(map("v: abc").Get("v", &d), "cfg.yaml:2: sec.v: expected a number, got 'abc'");
  check(map("v: \"5\"").Get("v", &d),
        "cfg.yaml:2: sec.v: expected a number, got '5' (quoted or tagged: a string)");
  check(map("v: .inf").Get("v", &d), "cfg.yaml:2: sec.v: expected a finite number, got '.inf'");
  check(map("v: nan").Get("v", &d), "cfg.yaml:2: sec.v: expected a finite number, got 'nan'");
  check(map("v: [1, 2]").Get("v", &d), "cfg.yaml:2: sec.v: expected a number, got a sequence of 2");
  check(map("v:").Get("v", &d), "cfg.yaml:2: sec.v: expected a number, got null");
  check(map("v: yes").Get("v", &b), "cfg.yaml:2: sec.v: expected true or false, got 'yes'");
  check(map("v: 1").Get("v", &b), "cfg.yaml:2: sec.v: expected true or false, got '1'");
  check(map("v: {a: 1}").Get("v", &s), "cfg.yaml:2: sec.v: expected a string, got a mapping");
  check(map("v: ~").Get("v", &s), "cfg.yaml:2: sec.v: expected a string, got null");
  check(map("v: 3").Get("v", &vi), "cfg.yaml:2: sec.v: expected a sequence [...], got '3'");
  check(map("v: [1, 2.5]").Get("v", &vi), "cfg.yaml:2: sec.v[1]: expected an integer, got '2.5'");
  check(map("v: [[1], 2]").Get("v", &vd),
        "cfg.yaml:2: sec.v[0]: expected a number, got a sequence of 1");
}

TEST(YamlMapTest, AcceptedScalarSpellings) {
  const YAML::Node root = Parse("a: TRUE\nb: False\nc: +3\nd: -2.5E2\ne: 'quoted'\nf: 12\n");
  YamlMap map(root, "cfg.yaml", "");
  bool a = false, b = true;
  int c = 0;
  double d = 0.0;
  std::string e, f;
  ASSERT_TRUE(map.Get("a", &a).ok());
  ASSERT_TRUE(map.Get("b", &b).ok());
  ASSERT_TRUE(map.Get("c", &c).ok());
  ASSERT_TRUE(map.Get("d", &d).ok());
  ASSERT_TRUE(map.Get("e", &e).ok());
  ASSERT_TRUE(map.Get("f", &f).ok());  // a string key may hold digits
  EXPECT_TRUE(a);
  EXPECT_FALSE(b);
  EXPECT_EQ(c, 3);
  EXPECT_EQ(d, -250.0);
  EXPECT_EQ(e, "quoted");
  EXPECT_EQ(f, "12");
  EXPECT_TRUE(map.CheckNoUnknownKeys().ok());
}

TEST(YamlMapTest, FailedGetLeavesValueUntouched) {
  YamlMap map(Parse("v: abc\n"), "cfg.yaml", "");
  double value = 4.0;
  EXPECT_FALSE(map.Get("v", &value).ok());
  EXPECT_EQ(value, 4.0);
  std::vector<int> values = {1};
  YamlMap list(Parse("v: [1, x]\n"), "cfg.yaml", "");
  EXPECT_FALSE(list.Get("v", &values).ok());
  EXPECT_THAT(values, ElementsAre(1));
}

TEST(YamlMapTest, UnknownKeyNamesLineKnownKeysAndSuggestion) {
  YamlMap region = RegionMap(
      "region:\n"
      "  band_px: 12\n"
      "  scael: 0.5\n"
      "  zzz: 1\n");
  int band_px = 0;
  double scale = 1.0;
  ASSERT_TRUE(region.Get("band_px", &band_px).ok());
  ASSERT_TRUE(region.GetOptional("scale", &scale).ok());
  const Status status = region.CheckNoUnknownKeys();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_EQ(status.message(),
            "cfg.yaml:3: region.scael: unknown key (did you mean 'scale'?); known keys: band_px, "
            "scale; 1 more unknown key");
}

TEST(YamlMapTest, UnknownKeyWithoutPlausibleSuggestion) {
  YamlMap map(Parse("alpha: 1\ncompletely_different: 2\n"), "cfg.yaml", "");
  int alpha = 0;
  ASSERT_TRUE(map.Get("alpha", &alpha).ok());
  const Status status = map.CheckNoUnknownKeys();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "cfg.yaml:2: completely_different: unknown key; known keys: alpha");
}

TEST(YamlMapTest, NodeAndGetFixedArrayMarkKeysKnown) {
  YamlMap map(Parse("sub: {a: 1}\nK: [1, 2, 3, 4]\n"), "cfg.yaml", "");
  EXPECT_TRUE(map.Node("sub").IsMap());
  EXPECT_FALSE(map.Node("absent").IsDefined());
  std::vector<double> k;
  ASSERT_TRUE(map.GetFixedArray("K", 4, &k).ok());
  EXPECT_THAT(k, ElementsAre(1, 2, 3, 4));
  EXPECT_TRUE(map.CheckNoUnknownKeys().ok());
}

TEST(YamlMapTest, HasDoesNotMarkKeyKnown) {
  YamlMap map(Parse("a: 1\n"), "cfg.yaml", "");
  EXPECT_TRUE(map.Has("a"));
  EXPECT_FALSE(map.Has("b"));
  EXPECT_FALSE(map.CheckNoUnknownKeys().ok());
}

TEST(YamlMapTest, GetFixedArrayWrongLength) {
  YamlMap map(Parse("cameras:\n  - K: [1, 2, 3]\n"), "rig.yaml", "");
  YamlMap camera(map.Node("cameras")[0], "rig.yaml", "cameras[0]");
  std::vector<double> k = {9};
  const Status status = camera.GetFixedArray("K", 4, &k);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "rig.yaml:2: cameras[0].K: expected 4 numbers, got 3");
  EXPECT_THAT(k, ElementsAre(9));
}

TEST(YamlMapTest, DuplicateKeyIsAnErrorNamingBothLines) {
  YamlMap region = RegionMap(
      "region:\n"
      "  band_px: 12\n"
      "  scale: 0.5\n"
      "  band_px: 14\n");
  const Status check = region.Check();
  ASSERT_FALSE(check.ok());
  EXPECT_EQ(check.message(), "cfg.yaml:4: region.band_px: duplicate key (first at line 2)");
  // Every accessor reports it, so a reader that skips Check() cannot read the first value.
  int band_px = 0;
  EXPECT_EQ(region.Get("band_px", &band_px).message(), check.message());
  EXPECT_EQ(region.GetOptional("scale", &band_px).message(), check.message());
  EXPECT_EQ(region.CheckNoUnknownKeys().message(), check.message());
  EXPECT_EQ(band_px, 0);
}

TEST(YamlMapTest, NotAMappingIsAnError) {
  YamlMap region = RegionMap("region: [1, 2]\nname: x\n");
  const Status status = region.Check();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(),
            "cfg.yaml:1: region: expected a mapping of keys, got a sequence of 2");
  int value = 0;
  EXPECT_FALSE(region.GetOptional("x", &value).ok());

  YamlMap scalar_root(Parse("just text\n"), "cfg.yaml", "");
  EXPECT_THAT(scalar_root.Check().message(),
              AllOf(StartsWith("cfg.yaml:1: the document: "), HasSubstr("got 'just text'")));
}

TEST(YamlMapTest, NonScalarKeyIsAnError) {
  YamlMap map(Parse("? [a, b]\n: 1\n"), "cfg.yaml", "sec");
  const Status status = map.Check();
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), AllOf(StartsWith("cfg.yaml:1: sec: "), HasSubstr("plain names")));
}

TEST(YamlMapTest, EmptySectionReadsAsEmptyMap) {
  YamlMap region = RegionMap("region:\nother: 1\n");
  EXPECT_TRUE(region.Check().ok());
  int band_px = 7;
  EXPECT_TRUE(region.GetOptional("band_px", &band_px).ok());
  EXPECT_EQ(band_px, 7);
  EXPECT_TRUE(region.CheckNoUnknownKeys().ok());
}

TEST(YamlMapTest, MissingKeyInEmptySectionClaimsNoLine) {
  // yaml-cpp marks an empty value at the token after it (here line 3), which would mislead.
  YamlMap region = RegionMap("region:\nother: 1\n");
  int band_px = 0;
  EXPECT_EQ(region.Get("band_px", &band_px).message(),
            "cfg.yaml: region.band_px: missing required key");
}

TEST(YamlMapTest, ConfigCodeAppliesToEveryError) {
  YamlMap map(Parse("a: x\nb: 1\nb: 2\n"), "run.yaml", "", StatusCode::kInvalidConfig);
  EXPECT_EQ(map.Check().code(), StatusCode::kInvalidConfig);
  YamlMap map2(Parse("a: x\nc: 1\n"), "run.yaml", "", StatusCode::kInvalidConfig);
  int a = 0;
  EXPECT_EQ(map2.Get("a", &a).code(), StatusCode::kInvalidConfig);
  EXPECT_EQ(map2.Get("missing", &a).code(), StatusCode::kInvalidConfig);
  EXPECT_EQ(map2.CheckNoUnknownKeys().code(), StatusCode::kInvalidConfig);
  const Status error = map2.Error("a", "x must be > 0");
  EXPECT_EQ(error.code(), StatusCode::kInvalidConfig);
  EXPECT_EQ(error.message(), "run.yaml:1: a: x must be > 0");
  EXPECT_EQ(map2.code(), StatusCode::kInvalidConfig);
}

TEST(YamlMapTest, LocationOfAbsentKeyIsTheMapping) {
  const YAML::Node root = Parse("x: 1\nsection:\n  a: 1\n");
  YamlMap section(root["section"], "cfg.yaml", "section");
  EXPECT_EQ(section.Location("a"), "cfg.yaml:3");
  EXPECT_EQ(section.Location("absent"), "cfg.yaml:3");
}

TEST(FormatYamlStringTest, RoundTripsThroughTheParser) {
  const std::vector<std::string> values = {"cam0",
                                           "../models/cat.obj",
                                           "/abs/path.obj",
                                           "true",
                                           "No",
                                           "null",
                                           "~",
                                           "",
                                           "1.5",
                                           "007",
                                           "-x",
                                           "a: b",
                                           "# hash",
                                           "x #y",
                                           "q\"uo",
                                           "back\\slash",
                                           "tab\there",
                                           "new\nline",
                                           "ünïcödé",
                                           ".inf",
                                           "[1]",
                                           "{a}",
                                           "*alias",
                                           "&anchor",
                                           "!tag",
                                           " lead"};
  for (const std::string& value : values) {
    const std::string formatted = FormatYamlString(value);
    const StatusOr<YAML::Node> node = ParseYaml("v: " + formatted + "\n", "f.yaml");
    ASSERT_TRUE(node.ok()) << formatted << ": " << node.status().message();
    YamlMap map(*node, "f.yaml", "");
    std::string read;
    ASSERT_TRUE(map.Get("v", &read).ok()) << formatted;
    EXPECT_EQ(read, value) << formatted;
  }
  EXPECT_EQ(FormatYamlString("cam0"), "cam0");
  EXPECT_EQ(FormatYamlString("../models/cat.obj"), "../models/cat.obj");
  EXPECT_EQ(FormatYamlString("true"), "\"true\"");
  EXPECT_EQ(FormatYamlString(""), "\"\"");
}

// ---------------------------------------------------------------------------------------------
// ApplyYamlOverrides

constexpr char kRunConfig[] =
    "render:\n"
    "  width: 320\n"
    "  height: 256\n"
    "solver:\n"
    "  rounds: 5\n"
    "  views: [cam0]\n"
    "empty:\n";

TEST(ApplyYamlOverridesTest, ReplacesValuesParsedAsYaml) {
  YAML::Node root = Parse(kRunConfig);
  ASSERT_TRUE(ApplyYamlOverrides({"render.width=640", "solver.views=[cam0, cam1]",
                                  "solver.verbose=true", "solver.rounds = 7"},
                                 &root)
                  .ok());
  YamlMap render(root["render"], "run.yaml", "render");
  int width = 0, height = 0;
  ASSERT_TRUE(render.Get("width", &width).ok());
  ASSERT_TRUE(render.Get("height", &height).ok());
  EXPECT_EQ(width, 640);
  EXPECT_EQ(height, 256);  // untouched

  YamlMap solver(root["solver"], "run.yaml", "solver");
  std::vector<std::string> views;
  bool verbose = false;
  int rounds = 0;
  ASSERT_TRUE(solver.Get("views", &views).ok());
  ASSERT_TRUE(solver.Get("verbose", &verbose).ok());
  ASSERT_TRUE(solver.Get("rounds", &rounds).ok());
  EXPECT_THAT(views, ElementsAre("cam0", "cam1"));
  EXPECT_TRUE(verbose);
  EXPECT_EQ(rounds, 7);
  EXPECT_TRUE(solver.CheckNoUnknownKeys().ok());
}

TEST(ApplyYamlOverridesTest, LaterOverridesWinAndValuesMayContainEquals) {
  YAML::Node root = Parse(kRunConfig);
  ASSERT_TRUE(
      ApplyYamlOverrides({"render.width=1", "render.width=2", "render.label=a=b"}, &root).ok());
  EXPECT_EQ(root["render"]["width"].as<int>(), 2);
  EXPECT_EQ(root["render"]["label"].as<std::string>(), "a=b");
  EXPECT_EQ(root["render"].size(), 3u);  // width replaced in place, not duplicated
}

TEST(ApplyYamlOverridesTest, CreatesMissingSectionsAndFillsEmptyOnes) {
  YAML::Node root = Parse(kRunConfig);
  ASSERT_TRUE(ApplyYamlOverrides({"a.b.c=1", "empty.x=2.5"}, &root).ok());
  EXPECT_EQ(root["a"]["b"]["c"].as<int>(), 1);
  EXPECT_EQ(root["empty"]["x"].as<double>(), 2.5);

  YAML::Node null_root;
  ASSERT_TRUE(ApplyYamlOverrides({"render.width=8"}, &null_root).ok());
  EXPECT_EQ(null_root["render"]["width"].as<int>(), 8);
}

TEST(ApplyYamlOverridesTest, TopLevelKeyWithoutSection) {
  YAML::Node root = Parse("seed: 1\n");
  ASSERT_TRUE(ApplyYamlOverrides({"seed=42"}, &root).ok());
  EXPECT_EQ(root["seed"].as<int>(), 42);
}

TEST(ApplyYamlOverridesTest, UnknownKeyIsCaughtByTheReaderWithoutFakeLine) {
  YAML::Node root = Parse(kRunConfig);
  ASSERT_TRUE(ApplyYamlOverrides({"render.widht=640"}, &root).ok());
  YamlMap render(root["render"], "run.yaml", "render", StatusCode::kInvalidConfig);
  int width = 0, height = 0;
  ASSERT_TRUE(render.Get("width", &width).ok());
  ASSERT_TRUE(render.Get("height", &height).ok());
  const Status status = render.CheckNoUnknownKeys();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kInvalidConfig);
  // The key came from the command line: no line number of run.yaml may be claimed.
  EXPECT_THAT(status.message(), AllOf(StartsWith("run.yaml: render.widht: unknown key"),
                                      HasSubstr("did you mean 'width'")));
}

TEST(ApplyYamlOverridesTest, OverriddenValueOfWrongTypeHasNoFakeLine) {
  YAML::Node root = Parse(kRunConfig);
  ASSERT_TRUE(ApplyYamlOverrides({"render.width=wide"}, &root).ok());
  YamlMap render(root["render"], "run.yaml", "render", StatusCode::kInvalidConfig);
  int width = 0;
  const Status status = render.Get("width", &width);
  ASSERT_FALSE(status.ok());
  // The key is on line 2 of run.yaml, but the value came from --set: no line is claimed.
  EXPECT_EQ(status.message(), "run.yaml: render.width: expected an integer, got 'wide'");
  EXPECT_EQ(status.code(), StatusCode::kInvalidConfig);
}

TEST(ApplyYamlOverridesTest, DescendingIntoScalarOrSequenceIsAnError) {
  for (const auto& [override_text, walked] : std::vector<std::pair<std::string, std::string>>{
           {"render.width.x=1", "render.width"}, {"solver.views.a=1", "solver.views"}}) {
    YAML::Node root = Parse(kRunConfig);
    const Status status = ApplyYamlOverrides({override_text}, &root);
    ASSERT_FALSE(status.ok()) << override_text;
    EXPECT_EQ(status.code(), StatusCode::kInvalidConfig);
    EXPECT_THAT(status.message(),
                AllOf(HasSubstr("override '" + override_text + "'"),
                      HasSubstr("'" + walked + "' is"), HasSubstr("not a section")));
    // Nothing was created under the scalar.
    EXPECT_EQ(root["render"]["width"].as<int>(), 320);
  }
}

TEST(ApplyYamlOverridesTest, MalformedOverridesNameTheOverride) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render.width", "expected section.key=value"},
      {"=5", "missing key"},
      {"render.width=", "missing value"},
      {"render.=5", "invalid component ''"},
      {".width=5", "invalid component ''"},
      {"render..width=5", "invalid component ''"},
      {"ren der.width=5", "invalid component 'ren der'"},
      {"render.width=[1, 2", "not valid YAML"},
      {"render.width=a: b: c", "not valid YAML"},
  };
  for (const auto& [override_text, problem] : cases) {
    YAML::Node root = Parse(kRunConfig);
    const Status status = ApplyYamlOverrides({override_text}, &root);
    ASSERT_FALSE(status.ok()) << override_text;
    EXPECT_EQ(status.code(), StatusCode::kInvalidConfig) << override_text;
    EXPECT_THAT(status.message(),
                AllOf(StartsWith("override '" + override_text + "': "), HasSubstr(problem)));
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << "one line";
  }
}

TEST(ApplyYamlOverridesTest, StopsAtFirstBadOverride) {
  YAML::Node root = Parse(kRunConfig);
  const Status status = ApplyYamlOverrides({"render.width=1", "bad", "render.height=2"}, &root);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), StartsWith("override 'bad'"));
  EXPECT_EQ(root["render"]["height"].as<int>(), 256);
}

TEST(ApplyYamlOverridesTest, RootThatIsNotAMappingIsAnError) {
  YAML::Node root = Parse("[1, 2]\n");
  const Status status = ApplyYamlOverrides({"a.b=1"}, &root);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(status.message(), HasSubstr("not a mapping"));
}

TEST(ApplyYamlOverridesTest, QuotedValueStaysAString) {
  YAML::Node root = Parse(kRunConfig);
  ASSERT_TRUE(ApplyYamlOverrides({"render.width=\"640\""}, &root).ok());
  YamlMap render(root["render"], "run.yaml", "render");
  int width = 0;
  EXPECT_THAT(render.Get("width", &width).message(), HasSubstr("quoted"));
  std::string text;
  ASSERT_TRUE(render.Get("width", &text).ok());
  EXPECT_EQ(text, "640");
}

}  // namespace
}  // namespace bcot
