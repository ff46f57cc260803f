#include "sylva/core/scene/ViewAnnotation.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "CairoSurface.h"
#include "sylva/core/base/Check.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/ImageProjection.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

std::string degrees(double radians, int decimals) {
    double value = std::fmod(radians / kDegree, 360.0);
    if (value < 0.0) {
        value += 360.0;
    }
    if (std::round(value * std::pow(10.0, decimals)) >= 360.0 * std::pow(10.0, decimals)) {
        value = 0.0;
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.*f\u00b0", decimals, value);
    return text;
}

// The column of the horizontal direction of `bearing` (radians clockwise from true north)
// at the camera, or nullopt when the image cannot show it or it falls outside the image.
std::optional<double> bearingColumn(const Camera& camera, const ImageProjection& projection,
                                    double bearing) {
    const glm::dmat3 frame =
        Ellipsoid::localFrame(camera.geodetic.latitude, camera.geodetic.longitude);
    const glm::dvec3 direction = std::sin(bearing) * frame[0] + std::cos(bearing) * frame[1];
    const std::optional<glm::dvec2> pixel = projection.pixelOf(camera.viewRotation() * direction);
    if (!pixel || pixel->x < 0.0 || pixel->x > projection.width()) {
        return std::nullopt;
    }
    return pixel->x;
}

// Bearing ticks every 5° up to 60° of HFOV, 10° up to 180°, 30° beyond.
void planBearings(const Camera& camera, const ImageProjection& projection,
                  ViewAnnotations& annotations) {
    const double field = projection.horizontalFov();
    annotations.bearingStep = (field <= 60.0 * kDegree + 1e-9    ? 5.0
                               : field <= 180.0 * kDegree + 1e-9 ? 10.0
                                                                 : 30.0) *
                              kDegree;
    const double step = annotations.bearingStep;
    const double heading = camera.heading();
    const long first = long(std::floor((heading - field / 2.0) / step)) - 1;
    const long last = long(std::ceil((heading + field / 2.0) / step)) + 1;
    for (long k = first; k <= last && k - first < 400; ++k) {
        if (std::optional<double> column = bearingColumn(camera, projection, double(k) * step)) {
            annotations.bearings.push_back({*column, degrees(double(k) * step, 0)});
        }
    }
}

void planProposal(const Camera& camera, const ImageProjection& projection,
                  const ViewProposal& proposal, ViewAnnotations& annotations) {
    annotations.extentText = "proposal " + degrees(proposal.leftBearing, 1) + "\u2013" +
                             degrees(proposal.rightBearing, 1) + " (" +
                             degrees(proposal.horizontalExtent, 1) + " wide)";
    const std::optional<double> left = bearingColumn(camera, projection, proposal.leftBearing);
    const std::optional<double> right = bearingColumn(camera, projection, proposal.rightBearing);
    if (left) {
        annotations.extentLeft = ViewMark{*left, degrees(proposal.leftBearing, 1)};
    }
    if (right) {
        annotations.extentRight = ViewMark{*right, degrees(proposal.rightBearing, 1)};
    }
    // The bracket over the part of the extent the image shows: from the left end (or the
    // image's left edge when the extent starts before it) to the right end (or the right edge).
    const double from = std::remainder(proposal.leftBearing - camera.heading(), 2.0 * kPi);
    const double to = from + proposal.horizontalExtent;
    const double half = projection.horizontalFov() / 2.0;
    if (to >= -half && from <= half) {
        annotations.bracket =
            std::make_pair(left ? *left : 0.0, right ? *right : double(annotations.width));
    }
    for (std::size_t i = 0; i < proposal.points.size(); ++i) {
        const std::optional<glm::dvec2> pixel = projection.pixelOfPoint(proposal.points[i]);
        if (!pixel || pixel->x < 0.0 || pixel->x > projection.width()) {
            continue;
        }
        annotations.parts.push_back(
            {pixel->x, i < proposal.labels.size() ? proposal.labels[i] : std::to_string(i + 1)});
    }
}

double textWidth(cairo_t* cairo, const std::string& value, bool bold) {
    cairo_select_font_face(cairo, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_text_extents_t extents;
    cairo_text_extents(cairo, value.c_str(), &extents);
    return extents.x_advance;
}

// Draws `value` with its left end at x − anchor × its width; returns that span's right end.
double text(cairo_t* cairo, const std::string& value, double x, double baseline, double anchor,
            bool bold) {
    const double width = textWidth(cairo, value, bold);
    cairo_move_to(cairo, x - anchor * width, baseline);
    cairo_show_text(cairo, value.c_str());
    return x + (1.0 - anchor) * width;
}

// Labels centred under `marks` in order, each left out when it would touch the previous
// one drawn (small images show fewer labels, never overlapping ones).
void labels(cairo_t* cairo, const std::vector<ViewMark>& marks, double baseline, double gap) {
    double end = -1e9;
    for (const ViewMark& mark : marks) {
        const double width = textWidth(cairo, mark.label, false);
        if (mark.column - width / 2.0 >= end + gap) {
            end = text(cairo, mark.label, mark.column, baseline, 0.5, false);
        }
    }
}

void verticalLine(cairo_t* cairo, double x, double top, double bottom) {
    cairo_move_to(cairo, x, top);
    cairo_line_to(cairo, x, bottom);
    cairo_stroke(cairo);
}

void setRed(cairo_t* cairo) {
    cairo_set_source_rgb(cairo, ViewAnnotation::kMarkRed[0] / 255.0,
                         ViewAnnotation::kMarkRed[1] / 255.0, ViewAnnotation::kMarkRed[2] / 255.0);
}

void drawTopBand(cairo_t* cairo, const ViewAnnotations& a) {
    const double f = a.fontSize;
    cairo_set_source_rgba(cairo, 1, 1, 1, 0.75);
    cairo_rectangle(cairo, 0, 0, a.width, a.topBand);
    cairo_fill(cairo);
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_font_size(cairo, f);
    const double titleEnd = text(cairo, a.title, 0.4 * f, 1.1 * f, 0.0, true);
    // The extent in words at the right, when it fits beside the title.
    if (!a.extentText.empty() &&
        a.width - 0.4 * f - textWidth(cairo, a.extentText, true) > titleEnd + f) {
        setRed(cairo);
        text(cairo, a.extentText, a.width - 0.4 * f, 1.1 * f, 1.0, true);
        cairo_set_source_rgb(cairo, 0, 0, 0);
    }
    cairo_set_line_width(cairo, a.lineWidth);
    cairo_move_to(cairo, 0, a.topBand - a.lineWidth / 2.0);
    cairo_line_to(cairo, a.width, a.topBand - a.lineWidth / 2.0);
    cairo_stroke(cairo);
    for (const ViewMark& tick : a.bearings) {
        verticalLine(cairo, tick.column, a.topBand - 0.55 * f, a.topBand);
    }
    labels(cairo, a.bearings, a.topBand - 0.75 * f, 0.6 * f);
}

void drawProposal(cairo_t* cairo, const ViewAnnotations& a) {
    const double f = a.fontSize;
    const double bandTop = a.height - a.bottomBand;
    if (a.bracket || !a.parts.empty()) {
        cairo_set_source_rgba(cairo, 1, 1, 1, 0.75);
        cairo_rectangle(cairo, 0, bandTop, a.width, a.bottomBand);
        cairo_fill(cairo);
    }
    setRed(cairo);
    cairo_set_line_width(cairo, a.lineWidth);
    for (const std::optional<ViewMark>& end : {a.extentLeft, a.extentRight}) {
        if (end) {
            verticalLine(cairo, end->column, a.topBand, bandTop);
        }
    }
    if (a.bracket) {
        const double y = bandTop + a.lineWidth / 2.0;
        cairo_move_to(cairo, a.bracket->first, y);
        cairo_line_to(cairo, a.bracket->second, y);
        cairo_stroke(cairo);
    }
    for (const ViewMark& part : a.parts) {
        verticalLine(cairo, part.column, a.partTickTop, a.partTickBottom);
    }
    std::vector<ViewMark> sorted = a.parts;
    std::sort(sorted.begin(), sorted.end(),
              [](const ViewMark& p, const ViewMark& q) { return p.column < q.column; });
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_font_size(cairo, f);
    labels(cairo, sorted, a.height - 0.35 * f, 0.3 * f);
}

}  // namespace

ViewAnnotations ViewAnnotation::plan(const Camera& camera, int width, int height,
                                     const std::string& id, const ViewProposal* proposal) {
    SYLVA_CHECK(width > 0 && height > 0);
    const ImageProjection projection(camera, width, height);
    ViewAnnotations annotations;
    annotations.width = width;
    annotations.height = height;
    annotations.fontSize = std::clamp(height / 24.0, 7.0, 48.0);
    const double f = annotations.fontSize;
    annotations.lineWidth = std::max(1.0, f / 9.0);
    annotations.topBand = 2.9 * f;
    annotations.bottomBand = 2.4 * f;
    annotations.partTickTop = height - annotations.bottomBand + 2.0 * annotations.lineWidth;
    annotations.partTickBottom = height - 1.3 * f;
    const char* kind = camera.projection == CameraProjection::Planar        ? "planar"
                       : camera.projection == CameraProjection::Cylindrical ? "cylindrical"
                                                                            : "equirectangular";
    annotations.title = id + "   view " + degrees(camera.heading(), 1) + "   HFOV " +
                        degrees(projection.horizontalFov(), 1) + " \u00d7 VFOV " +
                        degrees(projection.verticalFov(), 1) + "   " + kind;
    planBearings(camera, projection, annotations);
    if (proposal != nullptr) {
        planProposal(camera, projection, *proposal, annotations);
    }
    return annotations;
}

RgbaImage ViewAnnotation::draw(const RgbaImage& image, const ViewAnnotations& annotations) {
    SYLVA_CHECK(image.width == annotations.width && image.height == annotations.height);
    cairo_surface_t* surface = cairoSurfaceOf(image, CAIRO_FORMAT_RGB24);
    cairo_t* cairo = cairo_create(surface);
    drawTopBand(cairo, annotations);
    drawProposal(cairo, annotations);
    cairo_destroy(cairo);
    RgbaImage out = opaqueImageOf(surface, image.width, image.height);
    cairo_surface_destroy(surface);
    return out;
}

}  // namespace sylva
