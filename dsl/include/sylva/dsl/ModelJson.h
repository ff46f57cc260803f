// The evaluated model as JSON, for `sylva dump --json`, editors and the golden tests.
// Quantities keep SI values with their dimension; references are "@name" strings tagged
// with their kind, so the output says exactly what the renderer will see.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/model/ProjectModel.h"

namespace sylva::dsl {

// {"scenarios": [ {scenario, project, render, params, sources, ...}, ... ]} with
// `indent` spaces per level, ending in a newline.
std::string modelsToJson(const std::vector<ProjectModel>& models, int indent = 2);

}  // namespace sylva::dsl
