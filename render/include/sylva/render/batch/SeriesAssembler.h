// SeriesAssembler: the assemble phase of a batch run — everything made from images that
// are already on disk, without GL: the compare and blend images (read back, composed by
// ImageComparison; EXR series in linear radiance, others in 8-bit sRGB), the MP4s of
// path series (their PNG frames encoded by VideoEncoder, then removed) and one contact
// sheet per views block. Each file is written atomically, recorded in the run's manifest
// and reported through the run's listener; a failure is reported and the run goes on.
#pragma once

#include "sylva/render/batch/BatchRun.h"

namespace sylva::render {

class SeriesAssembler {
public:
    explicit SeriesAssembler(BatchRun& run) : run_(run) {}

    // Makes the Compare, Blend and Video jobs of the plan, in plan order (after its
    // images, which they read). Skips jobs that are current with resume; stops before
    // the next job once the run is cancelled. A video whose frames failed is not encoded.
    void assemble();
    // When the plan makes the whole series and no job failed: per views block with more
    // than one image, a sheet of 320-pixel thumbnails labelled with camera or path frame,
    // scenario, blend amount and time (videos and their frames are not shown), written to
    // OUTPUT/VIEW_contact_sheet.png. Unreadable images are left out.
    void writeContactSheets();

    // Whether Compare job `job` is a wireline (`compare { mode = wireline }`): drawn from
    // the depth buffers the image phase kept (BatchRun::keepDepth) over the left image.
    static bool isWireline(const BatchPlan& plan, const RenderJob& job);

private:
    void compose(const RenderJob& job);
    // The wireline image of `job`: what `right` adds to `left` (WirelineMasks by depth) and
    // the skyline, drawn over `left`'s displayed image (Photomontage::drawWireline).
    void composeWireline(const RenderJob& job, const Block& block);
    void encode(const RenderJob& job);

    BatchRun& run_;
};

}  // namespace sylva::render
