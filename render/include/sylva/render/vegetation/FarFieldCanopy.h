// FarFieldCanopy: the forest beyond the instance distance as a displaced canopy layer
// over the terrain (seed 000 ch. 6, "combined elevation map" = terrain + canopy proxy ×
// cover), so that forested ridges keep their silhouette to the horizon.
//
// Design. The seed ray-casts the CEM per pixel from a coarse proxy; Sylva's terrain is
// already a displaced geometry clipmap whose far rings have texels of tens to hundreds of
// metres, where a ray-cast heightfield would resolve nothing finer than the displaced
// mesh does. So the canopy is displacement, not ray casting: a second TerrainRenderer
// (the same static rings, TerrainRings, the same camera-relative vertex shader) whose
// height layer is the CEM and whose colour slot holds the canopy's albedo and cover
// (CanopyLayerSource), drawn with vegetation/farfield_canopy.frag into the G-buffer after
// the terrain (depth GREATER): lit by the same ShadingPass, receiving sun shadows there.
// Only the ring levels that reach beyond the hand-over start are updated and drawn, so
// the fine levels around the camera cost nothing. The canopy's layers are tiles like
// every other clipmap layer (cached, band-limited, produced by the Scheduler's workers),
// evaluated from the plants sources' density masks and the species' LoD heights
// (CanopyProfile), not from instance tiles: at 30 km a clipmap texel covers thousands
// of instances, which would have to be generated to be counted.
//
// Hand-over. Trees are drawn up to the instance distance D (render { vegetation_distance }),
// or less where even the smallest species drops below `minimumPixels`; the canopy fades
// in over `band` metres ending a margin (twice the canopy height) inside it, with the
// same screen-door pattern the trees fade out with (FarFieldFade), so each pixel of the
// band shows exactly one of them.
//
// Look: what the drawn trees show at the hand-over, on the render date. The crowns of the
// stand's coarsest LoD level in the species' leaf states (CanopyProfile::crowns, the
// phenology of each plants source at the date and the camera's latitude) give the opaque
// area a crown shows from above and from the side and the colour it shows; the shader
// keeps a pixel with the stand's cover along its ray from those areas (gaps show the
// terrain; January's leaf-off deciduous stand shows none), tints the stored full-leaf
// albedo to the crowns' colour, and gives each kept pixel the normal of a point on a crown
// facing the viewer, as the ray-cast ellipsoids do (no analytic self-shadowing: the
// shading pass shades those normals as it shades the trees' own). farfield_canopy.frag;
// docs/architecture.md.
//
// Not a shadow caster: the canopy casts no sun shadows (the near field would be shadowed
// by canopy that is not drawn there); it receives them through the shading pass.
// Needs a current GL 4.5 context for create(), update() and draw().
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/seasons/PlantDate.h"
#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/sources/plants/CanopyProfile.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/terrain/TerrainRenderer.h"
#include "sylva/render/vegetation/FarFieldFade.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {

struct FarFieldSettings {
    double band = 500.0;         // metres of the dithered hand-over; 0 = no far field
    double minimumCover = 0.05;  // canopy cover below which the terrain is left to show
};

struct FarFieldFrame {
    double instanceDistance = 0.0;  // metres: where the last trees are drawn
    double fadeStart = 0.0;         // metres: the canopy begins to take pixels
    double fadeEnd = 0.0;           // metres: the canopy has every pixel
    LevelRange levels;              // ring levels drawn
    bool drawn = false;             // false: no canopy this frame (no plants, no distance)
    bool waiting = false;           // interactive: a wanted level's tiles are still pending
};

class FarFieldCanopy {
public:
    // Fails when the canopy shader does not compile.
    static Result<std::unique_ptr<FarFieldCanopy>> create(const ShaderLibrary& library,
                                                          const TerrainSettings& settings);
    ~FarFieldCanopy();

    // Prepares the frame: the canopy sources of `layers` (built once per scenario), the
    // hand-over distances for `camera` (pixel angle in radians per pixel row, the
    // vegetation settings the trees are drawn with) and the canopy clipmaps of the
    // levels beyond the hand-over start within `terrainLevels`. Nothing is drawn when
    // there are no plants with a density mask, no instance distance or band is 0.
    // `date` (none: full leaf) and the camera's latitude set the species' leaf states
    // (the same as the drawn trees'); the crowns are re-evaluated only when they change.
    // Fails when a plant model cannot be built or a tile fails.
    Result<FarFieldFrame> update(const TerrainLayers& layers, TileProvider& provider,
                                 const Camera& camera, const LevelRange& terrainLevels,
                                 double heightAboveTerrain, double pixelAngle,
                                 const VegetationSettings& vegetation,
                                 const FarFieldSettings& settings, bool waitForTiles,
                                 const std::optional<PlantDate>& date = std::nullopt);

    // The crowns the canopy shows this frame (valid when the frame is drawn).
    const CanopyCrowns& crowns() const { return crowns_; }

    // The fade both sides of the hand-over use this frame (disabled when not drawn).
    FarFieldFade fade() const;

    // Draws the canopy into the bound G-buffer after the terrain (reversed-Z
    // `projection` with near plane `near`, width × height pixels).
    void draw(const Camera& camera, const glm::dmat4& projection, double near, int width,
              int height, bool ocean);

private:
    FarFieldCanopy() = default;
    struct Layers;  // the canopy sources of one scenario
    Result<const Layers*> layersFor(const TerrainLayers& layers);
    void updateCrowns(const Layers& canopy, const std::optional<PlantDate>& date, double latitude);

    std::unique_ptr<TerrainRenderer> rings_;
    std::map<std::uint64_t, std::unique_ptr<Layers>> built_;  // kept: workers may hold them
    const Layers* current_ = nullptr;
    FarFieldFrame frame_;
    FarFieldSettings settings_;
    // The crowns of current_'s dominant stand in crownStates_ (re-evaluated on change).
    const Layers* crownsOf_ = nullptr;
    std::vector<LeafState> crownStates_;
    CanopyCrowns crowns_;
};

}  // namespace sylva::render
