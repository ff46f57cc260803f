#include "sylva/core/scene/ViewpointSheet.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "CairoSurface.h"
#include "sylva/core/base/AtomicFile.h"

namespace sylva {
namespace {

constexpr double kPointsPerMetre = 72.0 / 0.0254;
constexpr double kLineSpacing = 1.3;  // line height / font size

int rowsPerColumn(const ViewpointRecord& record, const SheetLayout& layout) {
    return int((record.fields().size() + std::size_t(layout.columns) - 1) /
               std::size_t(layout.columns));
}

// Height (metres) of the metadata block: its rows plus a title line, or the location map
// with a line above it when that is taller.
double blockHeight(const ViewpointRecord& record, const SheetLayout& layout) {
    const double text = (rowsPerColumn(record, layout) + 1) * layout.fontSize * kLineSpacing;
    return layout.locationMap ? std::max(text, layout.mapSize + layout.fontSize * kLineSpacing)
                              : text;
}

cairo_status_t appendBytes(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

// Draws the sheet in metres (the caller's transform maps metres to device units).
void drawSheet(cairo_t* cairo, cairo_surface_t* picture, cairo_surface_t* map,
               const RgbaImage& image, const PrintFormat& print, const ViewpointRecord& record,
               const SheetLayout& layout, const glm::dvec2& page) {
    cairo_set_source_rgb(cairo, 1, 1, 1);
    cairo_paint(cairo);
    const double left = (page.x - print.width) / 2.0;
    const double top = layout.margin;
    cairo_save(cairo);
    cairo_translate(cairo, left, top);
    cairo_scale(cairo, print.width / image.width, print.height / image.height);
    cairo_set_source_surface(cairo, picture, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cairo), CAIRO_FILTER_GOOD);
    cairo_paint(cairo);
    cairo_restore(cairo);
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_line_width(cairo, 0.0002);
    cairo_rectangle(cairo, left, top, print.width, print.height);
    cairo_stroke(cairo);

    cairo_select_font_face(cairo, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cairo, layout.fontSize);
    const double line = layout.fontSize * kLineSpacing;
    double y = top + print.height + line;
    cairo_move_to(cairo, left, y);
    const ViewpointField* id = record.find("id");
    const ViewpointField* scenario = record.find("scenario");
    const std::string title = "Viewpoint " + (id ? id->text : std::string()) + " — " +
                              (scenario ? scenario->text : std::string());
    cairo_show_text(cairo, title.c_str());
    const int rows = rowsPerColumn(record, layout);
    const double mapWidth = layout.locationMap ? layout.mapSize + layout.margin : 0.0;
    const double columnWidth = (print.width - mapWidth) / layout.columns;
    for (std::size_t i = 0; i < record.fields().size(); ++i) {
        const ViewpointField& field = record.fields()[i];
        const double x = left + columnWidth * double(int(i) / rows);
        const double rowY = y + line * double(int(i) % rows + 1);
        cairo_select_font_face(cairo, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                               CAIRO_FONT_WEIGHT_BOLD);
        cairo_move_to(cairo, x, rowY);
        cairo_show_text(cairo, (field.label + ": ").c_str());
        cairo_select_font_face(cairo, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                               CAIRO_FONT_WEIGHT_NORMAL);
        cairo_show_text(cairo, field.text.c_str());
    }
    if (map != nullptr) {
        const double mapLeft = left + print.width - layout.mapSize;
        const double mapTop = top + print.height + line * 0.5;
        cairo_save(cairo);
        cairo_translate(cairo, mapLeft, mapTop);
        cairo_scale(cairo, layout.mapSize / layout.locationMap->width,
                    layout.mapSize / layout.locationMap->height);
        cairo_set_source_surface(cairo, map, 0, 0);
        cairo_pattern_set_filter(cairo_get_source(cairo), CAIRO_FILTER_GOOD);
        cairo_paint(cairo);
        cairo_restore(cairo);
        cairo_set_source_rgb(cairo, 0, 0, 0);
        cairo_rectangle(cairo, mapLeft, mapTop, layout.mapSize, layout.mapSize);
        cairo_stroke(cairo);
    }
}

Status writePdf(const RgbaImage& image, const PrintFormat& print, const ViewpointRecord& record,
                const SheetLayout& layout, const glm::dvec2& page,
                const std::filesystem::path& path) {
    std::string bytes;
    cairo_surface_t* surface = cairo_pdf_surface_create_for_stream(
        appendBytes, &bytes, page.x * kPointsPerMetre, page.y * kPointsPerMetre);
    cairo_t* cairo = cairo_create(surface);
    cairo_scale(cairo, kPointsPerMetre, kPointsPerMetre);
    cairo_surface_t* picture = cairoSurfaceOf(image, CAIRO_FORMAT_ARGB32);
    cairo_surface_t* map =
        layout.locationMap ? cairoSurfaceOf(*layout.locationMap, CAIRO_FORMAT_ARGB32) : nullptr;
    drawSheet(cairo, picture, map, image, print, record, layout, page);
    cairo_show_page(cairo);
    cairo_destroy(cairo);
    cairo_surface_finish(surface);
    const cairo_status_t status = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    cairo_surface_destroy(picture);
    if (map != nullptr) {
        cairo_surface_destroy(map);
    }
    if (status != CAIRO_STATUS_SUCCESS) {
        return Error{path.string() + ": cannot draw the sheet: " + cairo_status_to_string(status)};
    }
    if (Status written = writeFileAtomically(path, bytes); !written) {
        return Error{path.string() + ": cannot write the sheet: " + written.error().message};
    }
    return {};
}

Status writePng(const RgbaImage& image, const PrintFormat& print, const ViewpointRecord& record,
                const SheetLayout& layout, const glm::dvec2& page,
                const std::filesystem::path& path) {
    const double pixelsPerMetre = print.dpi / 0.0254;
    const int width = int(std::lround(page.x * pixelsPerMetre));
    const int height = int(std::lround(page.y * pixelsPerMetre));
    if (width > 32767 || height > 32767) {
        return Error{path.string() + ": the sheet at " + std::to_string(int(print.dpi)) +
                     " dpi is larger than 32767 pixels"};
    }
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t* cairo = cairo_create(surface);
    cairo_scale(cairo, pixelsPerMetre, pixelsPerMetre);
    cairo_surface_t* picture = cairoSurfaceOf(image, CAIRO_FORMAT_ARGB32);
    cairo_surface_t* map =
        layout.locationMap ? cairoSurfaceOf(*layout.locationMap, CAIRO_FORMAT_ARGB32) : nullptr;
    drawSheet(cairo, picture, map, image, print, record, layout, page);
    cairo_destroy(cairo);
    std::string bytes;
    const cairo_status_t status = cairo_surface_write_to_png_stream(surface, appendBytes, &bytes);
    cairo_surface_destroy(surface);
    cairo_surface_destroy(picture);
    if (map != nullptr) {
        cairo_surface_destroy(map);
    }
    if (status != CAIRO_STATUS_SUCCESS) {
        return Error{path.string() + ": cannot draw the sheet: " + cairo_status_to_string(status)};
    }
    if (Status written = writeFileAtomically(path, bytes); !written) {
        return Error{path.string() + ": cannot write the sheet: " + written.error().message};
    }
    return {};
}

}  // namespace

Result<glm::dvec2> ViewpointSheet::pageSize(const PrintFormat& print, const ViewpointRecord& record,
                                            const SheetLayout& layout) {
    const glm::dvec2 needed(print.width + 2 * layout.margin,
                            print.height + 2 * layout.margin + blockHeight(record, layout));
    if (layout.page.x <= 0.0 || layout.page.y <= 0.0) {
        return needed;
    }
    if (layout.page.x + 1e-9 < print.width || layout.page.y + 1e-9 < needed.y - layout.margin) {
        char buffer[200];
        std::snprintf(buffer, sizeof buffer,
                      "the image (%.0f x %.0f mm) and its metadata (%.0f mm) do not fit on a %.0f "
                      "x %.0f mm sheet",
                      print.width * 1e3, print.height * 1e3, blockHeight(record, layout) * 1e3,
                      layout.page.x * 1e3, layout.page.y * 1e3);
        return Error{buffer};
    }
    return layout.page;
}

Status ViewpointSheet::write(const RgbaImage& image, const PrintFormat& print,
                             const ViewpointRecord& record, const SheetLayout& layout,
                             const std::filesystem::path& pdf, const std::filesystem::path& png) {
    SYLVA_CHECK(print.valid() && image.width > 0 && image.height > 0);
    Result<glm::dvec2> page = pageSize(print, record, layout);
    if (!page) {
        return page.error();
    }
    if (!pdf.empty()) {
        if (Status written = writePdf(image, print, record, layout, page.value(), pdf); !written) {
            return written;
        }
    }
    if (!png.empty()) {
        if (Status written = writePng(image, print, record, layout, page.value(), png); !written) {
            if (!pdf.empty()) {
                std::error_code ignored;
                std::filesystem::remove(pdf, ignored);  // both or neither
            }
            return written;
        }
    }
    return {};
}

}  // namespace sylva
