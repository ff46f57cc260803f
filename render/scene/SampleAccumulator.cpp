#include "sylva/render/scene/SampleAccumulator.h"

#include <glad/gl.h>

#include <cmath>
#include <numeric>

#include "sylva/core/base/Check.h"

namespace sylva::render {

Result<std::unique_ptr<SampleAccumulator>> SampleAccumulator::create(const ShaderLibrary& library) {
    std::unique_ptr<SampleAccumulator> accumulator(new SampleAccumulator());
    Result<ShaderProgram> accumulate =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                        {GL_FRAGMENT_SHADER, "scene/accumulate_sample.frag"}});
    if (!accumulate) {
        return accumulate.error();
    }
    Result<ShaderProgram> resolve =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                        {GL_FRAGMENT_SHADER, "scene/resolve_samples.frag"}});
    if (!resolve) {
        return resolve.error();
    }
    accumulator->accumulate_ = std::move(accumulate.value());
    accumulator->resolve_ = std::move(resolve.value());
    accumulator->emptyVertexArray_ = createGlVertexArray();
    return accumulator;
}

std::vector<glm::dvec2> SampleAccumulator::pattern(int samples) {
    SYLVA_CHECK(samples >= 1 && samples <= kMaxSamples);
    std::vector<glm::dvec2> offsets;
    const int side = static_cast<int>(std::lround(std::sqrt(double(samples))));
    if (side * side == samples) {
        for (int y = 0; y < side; ++y) {
            for (int x = 0; x < side; ++x) {
                offsets.emplace_back((x + 0.5) / side - 0.5, (y + 0.5) / side - 0.5);
            }
        }
        return offsets;
    }
    // Generator of the rank-1 lattice: nearest N/φ, moved outwards until coprime with N.
    const double golden = (1.0 + std::sqrt(5.0)) / 2.0;
    const int nearest = static_cast<int>(std::lround(samples / golden));
    int generator = nearest;
    for (int step = 1; std::gcd(generator, samples) != 1; ++step) {
        generator = nearest + ((step % 2) != 0 ? (step + 1) / 2 : -(step / 2));
    }
    for (int i = 0; i < samples; ++i) {
        offsets.emplace_back((i + 0.5) / samples - 0.5,
                             ((i * generator) % samples + 0.5) / samples - 0.5);
    }
    return offsets;
}

glm::dmat4 SampleAccumulator::shifted(const glm::dmat4& projection, const glm::dvec2& offset,
                                      int width, int height) {
    // x_ndc = x_clip / w with w = −z: adding −2·dx/width · z to x_clip adds 2·dx/width to
    // x_ndc, i.e. moves every point dx pixels right (likewise y, up).
    glm::dmat4 result = projection;
    result[2][0] -= 2.0 * offset.x / width;
    result[2][1] -= 2.0 * offset.y / height;
    return result;
}

Status SampleAccumulator::begin(int width, int height, bool linear) {
    const int attachments = linear ? 2 : 1;
    if (sums_.id() == 0 || sums_.width() != width || sums_.height() != height ||
        sums_.colorCount() != attachments) {
        Result<Framebuffer> sums =
            Framebuffer::create(width, height,
                                linear ? std::vector<std::uint32_t>{GL_RGBA32F, GL_RGBA32F}
                                       : std::vector<std::uint32_t>{GL_RGBA32F},
                                false);
        if (!sums) {
            return sums.error();
        }
        sums_ = std::move(sums.value());
    }
    linear_ = linear;
    for (int i = 0; i < attachments; ++i) {
        sums_.clearColor(i, glm::vec4(0.0f));
    }
    return Status::success();
}

void SampleAccumulator::add(const Framebuffer& shaded, float weight) {
    SYLVA_CHECK(sums_.id() != 0 && shaded.width() == sums_.width() &&
                shaded.height() == sums_.height());
    sums_.bind();
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glBlendEquation(GL_FUNC_ADD);
    accumulate_.use();
    accumulate_.setInt("uDisplay", 0);
    accumulate_.setInt("uRadiance", 1);
    accumulate_.setInt("uLinear", linear_ ? 1 : 0);
    accumulate_.setFloat("uWeight", weight);
    glBindTextureUnit(0, shaded.colorTexture(0));
    glBindTextureUnit(1, linear_ ? shaded.colorTexture(1) : 0);
    drawFullScreen();
    glDisable(GL_BLEND);
}

void SampleAccumulator::resolve(const Framebuffer& target) {
    SYLVA_CHECK(target.width() == sums_.width() && target.height() == sums_.height());
    target.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    resolve_.use();
    resolve_.setInt("uDisplaySum", 0);
    resolve_.setInt("uRadianceSum", 1);
    resolve_.setInt("uLinear", linear_ ? 1 : 0);
    glBindTextureUnit(0, sums_.colorTexture(0));
    glBindTextureUnit(1, linear_ ? sums_.colorTexture(1) : 0);
    drawFullScreen();
}

void SampleAccumulator::drawFullScreen() const {
    glBindVertexArray(emptyVertexArray_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

}  // namespace sylva::render
