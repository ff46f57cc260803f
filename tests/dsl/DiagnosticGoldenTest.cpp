// Golden tests: every diagnostic code of the project language, rendered exactly.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "sylva/dsl/ProjectLoader.h"

namespace sylva::dsl {
namespace {

std::string renderOf(const std::string& text,
                     std::vector<std::pair<std::string, std::string>> defines = {}) {
    LoadOptions options;
    options.defines = std::move(defines);
    return loadProjectFromString(text, "test.sylva", options).render();
}

// The schema grows with every source kind; lists of names come from the registry.
std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) {
        out += (out.empty() ? "" : ", ") + name;
    }
    return out;
}
std::string sourceKindList() {
    return joined(SchemaRegistry::builtin().sourceKinds());
}
std::string attributeList(const std::string& kind) {
    std::vector<std::string> names;
    for (const AttributeSchema& attribute :
         SchemaRegistry::builtin().find("source", kind)->attributes) {
        names.push_back(attribute.name);
    }
    return joined(names);
}

TEST(DiagnosticGolden, UnexpectedCharacter) {
    EXPECT_EQ(renderOf(R"SYLVA(project { title = "a" } $$
)SYLVA"),
              R"SYLVA(error[E0004]: unexpected characters starting with '$'
 --> test.sylva:1:25
  |
1 | project { title = "a" } $$
  |                         ^^ not part of the language here
)SYLVA");
}

TEST(DiagnosticGolden, UnterminatedString) {
    EXPECT_EQ(renderOf(R"SYLVA(project { title = "abc }
)SYLVA"),
              R"SYLVA(error[E0102]: unclosed '{'
 --> test.sylva:1:9
  |
1 | project { title = "abc }
  |         ^ this '{' is never closed

error[E0005]: unterminated string
 --> test.sylva:1:19
  |
1 | project { title = "abc }
  |                   ^ this string is not closed on its line
)SYLVA");
}

TEST(DiagnosticGolden, UnterminatedComment) {
    EXPECT_EQ(renderOf(R"SYLVA(project { title = "a" }
/* outer /* inner */ still open
)SYLVA"),
              R"SYLVA(error[E0006]: unterminated block comment
 --> test.sylva:2:1
  |
2 | /* outer /* inner */ still open
  | ^^ this comment is never closed
)SYLVA");
}

TEST(DiagnosticGolden, InvalidEscape) {
    EXPECT_EQ(renderOf(R"SYLVA(project { title = "a\qb" }
)SYLVA"),
              R"SYLVA(error[E0007]: unknown escape sequence '\q'
 --> test.sylva:1:21
  |
1 | project { title = "a\qb" }
  |                     ^^ valid escapes are \" \\ \n \t
)SYLVA");
}

TEST(DiagnosticGolden, UnknownUnit) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { offset = 3kmh }
)SYLVA"),
              R"SYLVA(error[E0008]: unknown unit 'kmh'
 --> test.sylva:1:30
  |
1 | source n : noise { offset = 3kmh }
  |                              ^^^ not a unit
  = help: units are: m, km, cm, mm, deg, rad, %, px, s, min, h
)SYLVA");
}

TEST(DiagnosticGolden, InvalidColour) {
    EXPECT_EQ(renderOf(R"SYLVA(source c : hypsometric { height = @n; rock = #12345 }
source n : noise {}
)SYLVA"),
              R"SYLVA(error[E0009]: invalid colour '#12345'
 --> test.sylva:1:46
  |
1 | source c : hypsometric { height = @n; rock = #12345 }
  |                                              ^^^^^^ expected #RRGGBB or #RRGGBBAA
)SYLVA");
}

TEST(DiagnosticGolden, ExpectedEndOfLine) {
    EXPECT_EQ(renderOf(R"SYLVA(project {
    title = "a" "b"
}
)SYLVA"),
              R"SYLVA(error[E0101]: expected end of line or ';', found string
 --> test.sylva:2:17
  |
2 |     title = "a" "b"
  |                 ^^^ unexpected here
)SYLVA");
}

TEST(DiagnosticGolden, UnclosedBrace) {
    EXPECT_EQ(renderOf(R"SYLVA(project {
    title = "a"
)SYLVA"),
              R"SYLVA(error[E0102]: unclosed '{'
 --> test.sylva:1:9
  |
1 | project {
  |         ^ this '{' is never closed
)SYLVA");
}

TEST(DiagnosticGolden, UnclosedList) {
    EXPECT_EQ(renderOf(R"SYLVA(render {
    resolution = [320px, 180px
}
)SYLVA"),
              R"SYLVA(error[E0102]: unclosed '['
 --> test.sylva:2:18
  |
2 |     resolution = [320px, 180px
  |                  ^ this '[' is never closed
)SYLVA");
}

TEST(DiagnosticGolden, AttributeOutsideBlock) {
    EXPECT_EQ(renderOf(R"SYLVA(title = "x"
)SYLVA"),
              R"SYLVA(error[E0104]: attribute 'title' outside of a block
 --> test.sylva:1:1
  |
1 | title = "x"
  | ^^^^^ attributes belong inside a block such as 'project { ... }'
)SYLVA");
}

TEST(DiagnosticGolden, UnknownReference) {
    EXPECT_EQ(renderOf(R"SYLVA(source ground_graded : noise {}
source relief : normal_map {
    height = @ground_gradd
}
)SYLVA"),
              R"SYLVA(error[E0201]: unknown reference '@ground_gradd'
 --> test.sylva:3:14
  |
3 |     height = @ground_gradd
  |              ^^^^^^^^^^^^^ no source named 'ground_gradd'
  = help: did you mean '@ground_graded' (defined at test.sylva:1:8)?
)SYLVA");
}

TEST(DiagnosticGolden, DuplicateName) {
    EXPECT_EQ(renderOf(R"SYLVA(source a : noise {}
camera a { position = geo(1deg, 2deg) }
)SYLVA"),
              R"SYLVA(error[E0202]: duplicate name 'a'
 --> test.sylva:2:8
  |
2 | camera a { position = geo(1deg, 2deg) }
  |        ^ 'a' is already defined
note: 'a' first defined here at test.sylva:1:8
)SYLVA");
}

TEST(DiagnosticGolden, UnknownKeyword) {
    EXPECT_EQ(renderOf(R"SYLVA(sorce a : noise {}
)SYLVA"),
              R"SYLVA(error[E0203]: unknown block keyword 'sorce'
 --> test.sylva:1:1
  |
1 | sorce a : noise {}
  | ^^^^^ not a block keyword
  = help: did you mean 'source'?
  = help: block keywords are: param, project, source, scenario, camera, views, render, compare, blend, path, ztv, shadow_study, photo
)SYLVA");
}

TEST(DiagnosticGolden, UnknownKind) {
    EXPECT_EQ(renderOf(R"SYLVA(source a : noize {}
)SYLVA"),
              R"SYLVA(error[E0204]: unknown source kind 'noize'
 --> test.sylva:1:12
  |
1 | source a : noize {}
  |            ^^^^^ not a source kind
  = help: did you mean 'noise'?
  = help: source kinds are: )SYLVA" +
                  sourceKindList() + "\n");
}

TEST(DiagnosticGolden, MalformedHeader) {
    EXPECT_EQ(renderOf(R"SYLVA(camera { position = geo(1deg, 2deg) }
render r {}
)SYLVA"),
              R"SYLVA(error[E0205]: 'camera' block needs a name
 --> test.sylva:1:1
  |
1 | camera { position = geo(1deg, 2deg) }
  | ^^^^^^ write 'camera NAME { ... }'

error[E0205]: 'render' block takes no name
 --> test.sylva:2:8
  |
2 | render r {}
  |        ^ remove this name
)SYLVA");
}

TEST(DiagnosticGolden, DuplicateRender) {
    EXPECT_EQ(renderOf(R"SYLVA(render {}
render {}
)SYLVA"),
              R"SYLVA(error[E0206]: duplicate 'render' block
 --> test.sylva:2:1
  |
2 | render {}
  | ^^^^^^ second 'render' block
note: first 'render' block here at test.sylva:1:1
)SYLVA");
}

TEST(DiagnosticGolden, UndeclaredDefine) {
    EXPECT_EQ(renderOf(R"SYLVA(param relief : length = 2km
source n : noise { amplitude = @relief }
)SYLVA",
                       {{"releif", "3km"}}),
              R"SYLVA(error[E0207]: undeclared param 'releif'
 --> <command line>:1:4
  |
1 | -D releif=3km
  |    ^^^^^^ no param named 'releif'
  = help: did you mean 'relief' (defined at test.sylva:1:7)?
  = help: -D sets only params declared with 'param'
)SYLVA");
}

TEST(DiagnosticGolden, UnknownAttribute) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { amplitud = 2km }
)SYLVA"),
              R"SYLVA(error[E0208]: unknown attribute 'amplitud'
 --> test.sylva:1:20
  |
1 | source n : noise { amplitud = 2km }
  |                    ^^^^^^^^ not an attribute of noise source
  = help: did you mean 'amplitude'?
  = help: valid attributes: )SYLVA" +
                  attributeList("noise") + "\n");
}

TEST(DiagnosticGolden, DuplicateAttribute) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { seed = 1; seed = 2 }
)SYLVA"),
              R"SYLVA(error[E0209]: duplicate attribute 'seed'
 --> test.sylva:1:30
  |
1 | source n : noise { seed = 1; seed = 2 }
  |                              ^^^^ 'seed' is already set in this block
note: first set here at test.sylva:1:20
)SYLVA");
}

TEST(DiagnosticGolden, FieldAccess) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise {}
source m : normal_map { height = @n.height }
)SYLVA"),
              R"SYLVA(error[E0210]: unknown field 'height' of 'n'
 --> test.sylva:2:34
  |
2 | source m : normal_map { height = @n.height }
  |                                  ^^^^^^^^^ 'n' is a noise source without 'height'
  = help: fields are: )SYLVA" +
                  attributeList("noise") + "\n");
}

TEST(DiagnosticGolden, UnknownFunction) {
    EXPECT_EQ(renderOf(R"SYLVA(camera c { position = gep(1deg, 2deg) }
)SYLVA"),
              R"SYLVA(error[E0211]: unknown function 'gep'
 --> test.sylva:1:23
  |
1 | camera c { position = gep(1deg, 2deg) }
  |                       ^^^^^^^^^^^^^^^ not a function
  = help: did you mean 'geo'?
  = help: functions are: geo, min, max, clamp, interpolate, step, match, distance, destination
)SYLVA");
}

TEST(DiagnosticGolden, UnknownParamType) {
    EXPECT_EQ(renderOf(R"SYLVA(param p : lenght = 2km
source n : noise { amplitude = @p }
)SYLVA"),
              R"SYLVA(error[E0212]: unknown param type 'lenght'
 --> test.sylva:1:11
  |
1 | param p : lenght = 2km
  |           ^^^^^^ not a type
  = help: did you mean 'length'?
  = help: types are: number, length, angle, time, percentage, string, bool, colour
)SYLVA");
}

TEST(DiagnosticGolden, ParamCycle) {
    EXPECT_EQ(renderOf(R"SYLVA(param a = @b
param b = @a
source n : noise { amplitude = @a }
)SYLVA"),
              R"SYLVA(error[E0302]: param 'a' depends on itself
 --> test.sylva:2:11
  |
2 | param b = @a
  |           ^^ used while computing its own value
)SYLVA");
}

TEST(DiagnosticGolden, IncompatibleUnits) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { amplitude = 30deg + 2m }
)SYLVA"),
              R"SYLVA(error[E0401]: cannot add angle and length
 --> test.sylva:1:32
  |
1 | source n : noise { amplitude = 30deg + 2m }
  |                                ^^^^^^^^^^ the units do not match
)SYLVA");
}

TEST(DiagnosticGolden, WrongType) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { amplitude = "high" }
)SYLVA"),
              R"SYLVA(error[E0402]: expected length, found string
 --> test.sylva:1:32
  |
1 | source n : noise { amplitude = "high" }
  |                                ^^^^^^ 'amplitude' must be a length
)SYLVA");
}

TEST(DiagnosticGolden, DimensionMismatch) {
    EXPECT_EQ(renderOf(R"SYLVA(camera c { position = geo(1deg, 2deg); heading = 3m }
)SYLVA"),
              R"SYLVA(error[E0403]: expected angle, found length
 --> test.sylva:1:50
  |
1 | camera c { position = geo(1deg, 2deg); heading = 3m }
  |                                                  ^^ 'heading' must be an angle
)SYLVA");
}

TEST(DiagnosticGolden, OutOfRange) {
    EXPECT_EQ(renderOf(R"SYLVA(camera c { position = geo(1deg, 2deg); fov = 200deg }
)SYLVA"),
              R"SYLVA(error[E0404]: value out of range for 'fov'
 --> test.sylva:1:46
  |
1 | camera c { position = geo(1deg, 2deg); fov = 200deg }
  |                                              ^^^^^^ 200deg is above the maximum 170deg
)SYLVA");
}

TEST(DiagnosticGolden, ShadowDistanceOutOfRangeInScenarioOverride) {
    EXPECT_EQ(renderOf(R"SYLVA(source h : noise {}
scenario a { layers = [@h]; override render { shadow_distance = 5m } }
)SYLVA"),
              R"SYLVA(error[E0404]: value out of range for 'shadow_distance'
 --> test.sylva:2:65
  |
2 | scenario a { layers = [@h]; override render { shadow_distance = 5m } }
  |                                                                 ^^ 5m is below the minimum 20m
)SYLVA");
}

TEST(DiagnosticGolden, AmbientOcclusionOutOfRange) {
    EXPECT_EQ(renderOf(R"SYLVA(render { ambient_occlusion_radius = 500m }
)SYLVA"),
              R"SYLVA(error[E0404]: value out of range for 'ambient_occlusion_radius'
 --> test.sylva:1:37
  |
1 | render { ambient_occlusion_radius = 500m }
  |                                     ^^^^ 500m is above the maximum 100m
)SYLVA");
    EXPECT_EQ(renderOf(R"SYLVA(source h : noise {}
scenario a { layers = [@h]; override render { ambient_occlusion_strength = 2 } }
)SYLVA"),
              R"SYLVA(error[E0404]: value out of range for 'ambient_occlusion_strength'
 --> test.sylva:2:76
  |
2 | scenario a { layers = [@h]; override render { ambient_occlusion_strength = 2 } }
  |                                                                            ^ 2 is above the maximum 1
)SYLVA");
}

TEST(DiagnosticGolden, MissingRequired) {
    EXPECT_EQ(renderOf(R"SYLVA(camera ground { heading = 20deg }
)SYLVA"),
              R"SYLVA(error[E0405]: missing required attribute 'position'
 --> test.sylva:1:8
  |
1 | camera ground { heading = 20deg }
  |        ^^^^^^ camera 'ground' needs 'position'
  = help: position: geo(lat, lon[, height above the ellipsoid]) or [x, y[, height]] in the project CRS.
)SYLVA");
}

TEST(DiagnosticGolden, PortMismatch) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise {}
source c : hypsometric { height = @n }
source m : normal_map { height = @c }
)SYLVA"),
              R"SYLVA(error[E0406]: expected elevation, found image
 --> test.sylva:3:34
  |
3 | source m : normal_map { height = @c }
  |                                  ^^ 'c' is a hypsometric source, which outputs image
)SYLVA");
}

TEST(DiagnosticGolden, WrongBlockKind) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise {}
camera c { position = geo(1deg, 2deg) }
views v { cameras = [@n] }
)SYLVA"),
              R"SYLVA(error[E0406]: expected camera, found source
 --> test.sylva:3:22
  |
3 | views v { cameras = [@n] }
  |                      ^^ 'n' is a source
)SYLVA");
}

TEST(DiagnosticGolden, GeoArgumentCount) {
    EXPECT_EQ(renderOf(R"SYLVA(camera c { position = geo(1deg) }
)SYLVA"),
              R"SYLVA(error[E0407]: geo() takes 2 or 3 arguments, found 1
 --> test.sylva:1:23
  |
1 | camera c { position = geo(1deg) }
  |                       ^^^^^^^^^ write geo(latitude, longitude[, height])
)SYLVA");
}

TEST(DiagnosticGolden, DivisionByZero) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { amplitude = 2km / 0 }
)SYLVA"),
              R"SYLVA(error[E0408]: division by zero
 --> test.sylva:1:38
  |
1 | source n : noise { amplitude = 2km / 0 }
  |                                      ^ this is zero
)SYLVA");
}

TEST(DiagnosticGolden, ParamWithoutValue) {
    EXPECT_EQ(renderOf(R"SYLVA(param p : length "doc"
source n : noise { amplitude = @p }
)SYLVA"),
              R"SYLVA(error[E0409]: param 'p' has no value
 --> test.sylva:1:7
  |
1 | param p : length "doc"
  |       ^ declared without a default
  = help: give it a default ('param p = ...') or set it with -D p=...
)SYLVA");
}

TEST(DiagnosticGolden, BareNumberWarning) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { amplitude = 2500 }
camera c { position = geo(46.5, 8deg) }
)SYLVA"),
              R"SYLVA(warning[W0101]: bare number where a length is expected; assuming metres
 --> test.sylva:1:32
  |
1 | source n : noise { amplitude = 2500 }
  |                                ^^^^ read as 2500m

warning[W0101]: bare number where an angle is expected; assuming degrees
 --> test.sylva:2:27
  |
2 | camera c { position = geo(46.5, 8deg) }
  |                           ^^^^ read as 46.5deg
)SYLVA");
}

TEST(DiagnosticGolden, UnusedParam) {
    EXPECT_EQ(renderOf(R"SYLVA(param spare = 3
project {}
)SYLVA"),
              R"SYLVA(warning[W0201]: unused param 'spare'
 --> test.sylva:1:7
  |
1 | param spare = 3
  |       ^^^^^ declared here but never used
)SYLVA");
}

TEST(DiagnosticGolden, NestingTooDeep) {
    EXPECT_EQ(
        renderOf(
            R"SYLVA(param p = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]
)SYLVA"),
        R"SYLVA(error[E0103]: expression nested too deeply
 --> test.sylva:1:75
  |
1 | param p = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]
  |                                                                           ^ nesting is limited to 64 levels
)SYLVA");
}

TEST(DiagnosticGolden, InvalidNumber) {
    EXPECT_EQ(renderOf(R"SYLVA(source n : noise { seed = 1e999 }
)SYLVA"),
              R"SYLVA(error[E0009]: number '1e999' is too large
 --> test.sylva:1:27
  |
1 | source n : noise { seed = 1e999 }
  |                           ^^^^^ does not fit in a double
)SYLVA");
}

TEST(DiagnosticGolden, DefineSyntaxError) {
    EXPECT_EQ(renderOf(R"SYLVA(param h : length = 1m
source n : noise { amplitude = @h }
)SYLVA",
                       {{"h", "2km +"}}),
              R"SYLVA(error[E0101]: expected a value, found end of file
 --> <command line>:1:11
  |
1 | -D h=2km +
  |           ^ expected a value
)SYLVA");
}

}  // namespace
}  // namespace sylva::dsl
