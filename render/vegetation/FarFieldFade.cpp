#include "sylva/render/vegetation/FarFieldFade.h"

namespace sylva::render {

void FarFieldFade::apply(ShaderProgram& program, const glm::dmat4& projection, double near,
                         int width, int height) const {
    // ndc = p00 x / -z - p20, ndc = 2 pixel / width - 1, so x / -z = pixel * 2 / (width p00)
    // + (p20 - 1) / p00; likewise for y.
    const double p00 = projection[0][0], p11 = projection[1][1];
    const double p20 = projection[2][0], p21 = projection[2][1];
    program.setVec4("uFarFieldRay",
                    glm::vec4(float(2.0 / (width * p00)), float(2.0 / (height * p11)),
                              float((p20 - 1.0) / p00), float((p21 - 1.0) / p11)));
    program.setVec4(
        "uFarFieldFade",
        glm::vec4(float(start), enabled() ? float(1.0 / (end - start)) : 0.0f, float(near), 0.0f));
}

}  // namespace sylva::render
