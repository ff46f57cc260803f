#include "sylva/core/sources/Source.h"

#include "sylva/core/base/Hash.h"

namespace sylva {

Source::Source(std::string name, std::string kind, PortType output, int channels)
    : name_(std::move(name)), kind_(std::move(kind)), output_(output), channels_(channels) {}

Source::~Source() = default;

void Source::addInput(const Source* input) {
    SYLVA_CHECK(input != nullptr);
    inputs_.push_back(input);
}

void Source::setParameterHash(std::uint64_t parameterHash) {
    ContentHash hash;
    hash.add(kind_).add(parameterHash).add(channels_);
    for (const Source* input : inputs_) {
        hash.add(input->contentHash());
    }
    contentHash_ = hash.value();
}

}  // namespace sylva
