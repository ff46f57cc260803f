#include "sylva/core/terrain/Clipmap.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva {
namespace {

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}
std::int64_t floorMod(std::int64_t a, std::int64_t b) {
    return a - floorDiv(a, b) * b;
}

}  // namespace

double ClipmapWindow::texelWidth(int size) const {
    return 2.0 * std::numbers::pi / static_cast<double>(totalColumns(size));
}
double ClipmapWindow::texelHeight(int size) const {
    return std::numbers::pi / static_cast<double>(totalRows(size));
}

Clipmap::Clipmap(int levelCount, int size, int channels)
    : size_(size), channels_(channels), levels_(static_cast<std::size_t>(levelCount)) {
    SYLVA_CHECK(levelCount > 0 && size > 0 && size % 2 == 0 && channels > 0);
    for (Level& level : levels_) {
        level.texels.assign(static_cast<std::size_t>(size) * size * channels, 0.0f);
    }
}

double Clipmap::ringRadius(int level) {
    return std::ldexp(std::numbers::pi, -level);
}

ClipmapWindow Clipmap::windowFor(int level, double latitude, double longitude, int size,
                                 int levelOffset) {
    SYLVA_CHECK(levelOffset >= 1);
    ClipmapWindow window;
    window.level = std::max(0, level - levelOffset);
    const double radius = ringRadius(level);
    const double colatitude = std::numbers::pi / 2 - latitude;
    const double texelHeight = std::numbers::pi / (double(TileKey::rows(window.level)) * size);
    // Longitude half-width of the ring's disk around the focus (spherical cap), plus a
    // quarter for safety and two texels for bilinear filtering; full circle when the
    // disk contains a pole (§5.4.1).
    window.lonReduction = window.level + 1;
    if (radius < colatitude && radius < std::numbers::pi - colatitude) {
        const double halfWidth = std::asin(std::min(1.0, std::sin(radius) / std::sin(colatitude)));
        for (int k = 0; k <= window.level + 1; ++k) {
            const double texelWidth =
                2.0 * std::numbers::pi / (double(TileKey::columns(window.level, k)) * size);
            const double halfSpan = texelWidth * size / 2;
            if (halfSpan >= 1.25 * halfWidth + 2 * texelWidth) {
                window.lonReduction = k;
                break;
            }
        }
    }
    const std::int64_t columns = window.totalColumns(size);
    const double texelWidth = window.texelWidth(size);
    double x = (longitude + std::numbers::pi) / texelWidth;
    x -= std::floor(x / double(columns)) * double(columns);
    const auto focusX = static_cast<std::int64_t>(std::floor(x));
    const auto focusY =
        static_cast<std::int64_t>(std::floor((std::numbers::pi / 2 - latitude) / texelHeight));
    window.originX = floorMod(focusX - size / 2, columns);
    window.originY = focusY - size / 2;
    return window;
}

std::vector<TileKey> Clipmap::tilesFor(const ClipmapWindow& window, int size) {
    // The same tile arithmetic as copyRect over the full window.
    const std::int64_t n = size;
    const std::int64_t columns = TileKey::columns(window.level, window.lonReduction);
    const std::int64_t totalRows = window.totalRows(size);
    const std::int64_t rowFirst =
        floorDiv(std::clamp<std::int64_t>(window.originY, 0, totalRows - 1), n);
    const std::int64_t rowLast =
        floorDiv(std::clamp<std::int64_t>(window.originY + n - 1, 0, totalRows - 1), n);
    const std::int64_t columnFirst = floorDiv(window.originX, n);
    std::vector<TileKey> keys;
    for (std::int64_t row = rowFirst; row <= rowLast; ++row) {
        for (std::int64_t column = columnFirst; column <= floorDiv(window.originX + n - 1, n);
             ++column) {
            const TileKey key{window.level, window.lonReduction,
                              static_cast<std::int32_t>(floorMod(column, columns)),
                              static_cast<std::int32_t>(row)};
            if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
                keys.push_back(key);
            }
        }
    }
    return keys;
}

const ClipmapWindow& Clipmap::window(int level) const {
    SYLVA_CHECK(valid(level));
    return *levels_.at(level).window;
}

void Clipmap::invalidate(int level) {
    levels_.at(level).window.reset();
}

std::vector<Clipmap::Region> Clipmap::takeDirtyRegions() {
    std::vector<Region> result;
    result.swap(dirty_);
    return result;
}

float Clipmap::texel(int level, std::int64_t globalX, std::int64_t globalY, int channel) const {
    const std::size_t tx = static_cast<std::size_t>(floorMod(globalX, size_));
    const std::size_t ty = static_cast<std::size_t>(floorMod(globalY, size_));
    return levels_.at(level).texels[(ty * size_ + tx) * channels_ + channel];
}

Status Clipmap::update(int level, const ClipmapWindow& window, const Fetch& fetch) {
    Level& state = levels_.at(level);
    const std::int64_t n = size_;
    const std::int64_t nx = window.originX, ny = window.originY;
    bool full = !state.window || state.window->level != window.level ||
                state.window->lonReduction != window.lonReduction;
    std::int64_t dx = 0, dy = 0;
    if (!full) {
        const std::int64_t columns = window.totalColumns(size_);
        dx = floorMod(nx - state.window->originX, columns);
        if (dx > columns / 2) {
            dx -= columns;  // the shorter way round the globe
        }
        dy = ny - state.window->originY;
        full = std::abs(dx) >= n || std::abs(dy) >= n;
        if (columns == n) {
            dx = 0;  // the window spans the whole circle: columns never change
        }
    }
    // Invalidate first so a failed fetch leaves no half-valid level behind.
    state.window.reset();
    Status status;
    if (full) {
        status = copyRect(level, window, nx, ny, nx + n, ny + n, fetch);
    } else {
        // Rows that entered the window, across its full width...
        std::int64_t keepY0 = ny, keepY1 = ny + n;
        if (dy > 0) {
            status = copyRect(level, window, nx, ny + n - dy, nx + n, ny + n, fetch);
            keepY1 = ny + n - dy;
        } else if (dy < 0) {
            status = copyRect(level, window, nx, ny, nx + n, ny - dy, fetch);
            keepY0 = ny - dy;
        }
        // ...then columns that entered, over the remaining rows.
        if (status && dx > 0) {
            status = copyRect(level, window, nx + n - dx, keepY0, nx + n, keepY1, fetch);
        } else if (status && dx < 0) {
            status = copyRect(level, window, nx, keepY0, nx - dx, keepY1, fetch);
        }
    }
    if (status) {
        state.window = window;
    }
    return status;
}

Status Clipmap::copyRect(int level, const ClipmapWindow& window, std::int64_t x0, std::int64_t y0,
                         std::int64_t x1, std::int64_t y1, const Fetch& fetch) {
    const std::int64_t n = size_;
    const std::int64_t columns = TileKey::columns(window.level, window.lonReduction);
    const std::int64_t totalRows = window.totalRows(size_);
    std::vector<float>& texels = levels_.at(level).texels;
    // Split at multiples of the size: these are both tile borders and the toroidal
    // wrap, so every piece comes from one tile and lands in one texture rectangle.
    for (std::int64_t py = y0; py < y1;) {
        const std::int64_t pyEnd = std::min(y1, (floorDiv(py, n) + 1) * n);
        for (std::int64_t px = x0; px < x1;) {
            const std::int64_t pxEnd = std::min(x1, (floorDiv(px, n) + 1) * n);
            const std::int64_t tileX = floorMod(floorDiv(px, n), columns);
            TilePointer tile;
            std::int64_t tileY = -1;
            for (std::int64_t gy = py; gy < pyEnd; ++gy) {
                // Rows beyond a pole repeat the pole row (never sampled by the rings).
                const std::int64_t sourceRow = std::clamp<std::int64_t>(gy, 0, totalRows - 1);
                const std::int64_t rowTile = floorDiv(sourceRow, n);
                if (rowTile != tileY) {
                    TileKey key{window.level, window.lonReduction, static_cast<std::int32_t>(tileX),
                                static_cast<std::int32_t>(rowTile)};
                    Result<TilePointer> fetched = fetch(key);
                    if (!fetched) {
                        return fetched.error();
                    }
                    tile = fetched.value();
                    SYLVA_CHECK(tile->size() == size_ && tile->channels() == channels_);
                    tileY = rowTile;
                }
                const float* source = tile->row(static_cast<int>(sourceRow - rowTile * n));
                float* target =
                    texels.data() + static_cast<std::size_t>(floorMod(gy, n)) * n * channels_;
                for (std::int64_t gx = px; gx < pxEnd; ++gx) {
                    const std::int64_t ix = floorMod(gx, n);
                    const float* from =
                        source + (static_cast<std::size_t>(ix) + tile->border()) * channels_;
                    std::copy(from, from + channels_, target + ix * channels_);
                }
            }
            dirty_.push_back({level, static_cast<int>(floorMod(px, n)),
                              static_cast<int>(floorMod(py, n)), static_cast<int>(pxEnd - px),
                              static_cast<int>(pyEnd - py)});
            texelsCopied_ += static_cast<std::uint64_t>((pxEnd - px) * (pyEnd - py));
            px = pxEnd;
        }
        py = pyEnd;
    }
    return Status::success();
}

}  // namespace sylva
