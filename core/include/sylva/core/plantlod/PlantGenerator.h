// PlantGenerator: procedural trees after Weber & Penn 1995, "Creation and Rendering of
// Realistic Trees" (SIGGRAPH '95). A tree is a recursion of stem levels; each level has
// the paper's parameters (length, curve, splits, branch count, down and rotate angles,
// taper), leaves are alpha-masked quads on the last level with a procedurally drawn leaf
// texture. The result is a PlantModel with a branch skeleton (one SkeletonSegment per
// curve segment of every stem), so seed 001 §3.4's line hierarchy needs no reconstruction.
//
// Frame: metres, +Z up, the trunk base at the origin. Deterministic: the same
// (preset, seed, leaf target) gives bit-identical output on every run and platform that
// uses IEEE float (no std:: distributions, whose results are implementation-defined).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

// Parameters of one stem level (Weber & Penn Table 1, "n" prefixed there).
// Angles in radians, lengths as fractions of the parent as in the paper.
struct StemLevelParameters {
    float length = 1.0f;           // nLength: child length relative to the parent (level 0: scale)
    float lengthVariation = 0.0f;  // nLengthV
    float taper = 1.0f;            // nTaper: 0 cylinder, 1 cone to a point
    int curveResolution = 3;       // nCurveRes: segments per stem
    float curve = 0.0f;            // nCurve: total bend over the stem
    float curveBack = 0.0f;        // nCurveBack: bend back over the second half (S shapes)
    float curveVariation = 0.0f;   // nCurveV: random bend per segment
    float segmentSplits = 0.0f;    // nSegSplits: clones per segment (error-diffused)
    float splitAngle = 0.0f;       // nSplitAngle
    float splitAngleVariation = 0.0f;
    int branches = 0;                 // nBranches: children of this level per parent (max)
    float downAngle = 0.0f;           // nDownAngle: child angle from the parent axis
    float downAngleVariation = 0.0f;  // nDownAngleV (negative: varies along the parent)
    float rotate = 0.0f;  // nRotate: spiral step around the parent (negative: alternate)
    float rotateVariation = 0.0f;
    int radialSegments = 6;  // tube sides of this level's meshes
};

enum class TreeShape : std::uint8_t {
    Conical,
    Spherical,
    Hemispherical,
    Cylindrical,
    TaperedCylindrical,
    Flame,
    InverseConical,
    TendFlame,
};

struct TreeParameters {
    std::string name;
    TreeShape shape = TreeShape::Spherical;
    float baseSize = 0.3f;  // fraction of the trunk without branches
    float scale = 10.0f;    // metres: trunk length scale
    float scaleVariation = 0.0f;
    float ratio = 0.02f;      // trunk radius / trunk length
    float ratioPower = 1.3f;  // child radius = parent radius * (child/parent length)^ratioPower
    float flare = 0.3f;       // trunk base widening
    int baseSplits = 0;       // trunk clones at the base of the crown
    std::vector<StemLevelParameters> levels;  // [0] is the trunk
    // Leaves: on the last stem level, placed like one more level of children.
    int leaves = 0;           // leaves per last-level stem (before the leaf target)
    float leafScale = 0.1f;   // metres, leaf length
    float leafScaleX = 0.5f;  // width / length
    float leafDownAngle = 0.8f;
    float leafRotate = 2.4f;
    bool needles = false;                     // narrow leaf texture
    glm::vec3 barkColor{0.3f, 0.22f, 0.15f};  // linear RGB
    glm::vec3 leafColor{0.1f, 0.3f, 0.05f};   // linear RGB
    float attractionUp = 0.0f;  // AttractionUp: twigs bend towards (+) or away from the sky
};

struct PlantGeneratorOptions {
    std::uint64_t seed = 1;
    // Exact number of leaves (quads) when set; leaves are distributed over the stems in
    // proportion to the preset's per-stem counts, and their size scales with
    // sqrt(preset count / target) so the crown keeps its leaf area (Weber & Penn's
    // "leaf quality" factor).
    std::optional<int> leafCount;
    int leafTextureSize = 128;  // pixels, square
};

class PlantGenerator {
public:
    // The preset names: oak, conifer, birch, bush.
    static std::vector<std::string> presetNames();
    // The parameters of a preset; an error naming the known presets when unknown.
    static Result<TreeParameters> preset(const std::string& name);
    // Builds the tree. Fails only on invalid parameters (message names the field).
    static Result<PlantModel> generate(const TreeParameters& parameters,
                                       const PlantGeneratorOptions& options);
    // An RGBA8 leaf image (sRGB colour, alpha 0 outside the blade) with midrib and veins.
    static PlantTexture drawLeafTexture(int size, glm::vec3 linearColor, bool needles);
};

}  // namespace sylva
