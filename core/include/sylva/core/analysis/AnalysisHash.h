// AnalysisHash: what decides the files of an analysis block (`ztv`, `shadow_study`), for
// `sylva analyse --resume`: the block's content hash (its attributes and, through the
// DSL's hashing, the content hashes of the sources it references), the stamp (path,
// size, modification time) of every file those sources read — directly or through their
// inputs: `file`, `model` and `lod` attributes — and kAnalysisVersion, raised when the
// analysis code changes its results. A block whose hash is unchanged computes the same
// files, so a resumed run skips it.
#pragma once

#include <cstdint>

#include "sylva/core/model/ProjectModel.h"

namespace sylva {

// Raised whenever core/analysis changes what a block writes.
inline constexpr std::uint64_t kAnalysisVersion = 3;

// Never fails: a file that cannot be stamped (missing) hashes as missing, so it changes
// the hash when it appears.
std::uint64_t analysisHash(const ProjectModel& model, const Block& block);

}  // namespace sylva
