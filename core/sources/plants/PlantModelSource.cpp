#include "sylva/core/sources/plants/PlantModelSource.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <system_error>

#include "sylva/core/base/Hash.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"
#include "sylva/core/plantlod/PlantSidecar.h"
#include "sylva/core/plantlod/PlodFile.h"

namespace sylva {
namespace {

// Bumped whenever the LoD builder's output for the same input changes, so caches built
// by older code are not reused.
constexpr std::uint32_t kBuilderVersion = 2;

std::string lowerExtension(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    for (char& c : extension) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return extension;
}

// Adds the file's bytes (or, when unreadable, its name: asset() reports the error).
void addFile(ContentHash& hash, const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        hash.add(std::string_view("unreadable")).add(path.string());
        return;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    hash.add(std::string_view(bytes));
}

std::string hex(std::uint64_t value) {
    char text[32];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

}  // namespace

PlantModelSource::PlantModelSource(std::string name, PlantModelParameters parameters,
                                   std::string where)
    : Source(std::move(name), "plant_model", PortType::PlantModel, 0),
      parameters_(std::move(parameters)),
      where_(std::move(where)) {
    ContentHash hash;
    hash.add(kBuilderVersion).add(parameters_.preset);
    hash.add(parameters_.leaves.has_value()).add(parameters_.leaves.value_or(0));
    hash.add(parameters_.seed).add(parameters_.billboards);
    hash.add(!parameters_.file.empty());
    if (!parameters_.file.empty()) {
        addFile(hash, parameters_.file);
        std::error_code error;
        const std::filesystem::path sidecar = PlantSidecar::pathFor(parameters_.file);
        if (std::filesystem::exists(sidecar, error)) {
            addFile(hash, sidecar);
        }
    }
    hash.add(!parameters_.lod.empty());
    if (!parameters_.lod.empty()) {
        addFile(hash, parameters_.lod);
    }
    setParameterHash(hash.value());
}

Result<std::unique_ptr<PlantModelSource>> PlantModelSource::make(std::string name,
                                                                 PlantModelParameters parameters,
                                                                 std::string where) {
    const std::string label = where.empty() ? "plant_model '" + name + "': " : where;
    if (parameters.preset.empty() == parameters.file.empty()) {
        return Error{label +
                     "give either `preset` (a generated tree) or `file` (a model or "
                     ".plod), not " +
                     (parameters.preset.empty() ? "neither" : "both")};
    }
    if (!parameters.preset.empty()) {
        if (Result<TreeParameters> preset = PlantGenerator::preset(parameters.preset); !preset) {
            return Error{label + preset.error().message};
        }
    }
    if (parameters.leaves && parameters.preset.empty()) {
        return Error{label + "`leaves` applies to generated trees (`preset`) only"};
    }
    if (parameters.leaves && *parameters.leaves < 1) {
        return Error{label + "`leaves` must be at least 1"};
    }
    std::error_code error;
    if (!parameters.file.empty()) {
        const std::string extension = lowerExtension(parameters.file);
        if (extension != ".gltf" && extension != ".glb" && extension != ".obj" &&
            extension != ".plod") {
            return Error{label + parameters.file.string() + ": unsupported plant model type '" +
                         extension + "' (.gltf, .glb, .obj or .plod)"};
        }
        if (!std::filesystem::is_regular_file(parameters.file, error)) {
            return Error{label + parameters.file.string() + ": file not found"};
        }
        if (extension == ".plod" && !parameters.lod.empty()) {
            return Error{label + "`lod` needs a model `file` (or `preset`); " +
                         parameters.file.string() + " is already a .plod"};
        }
        if (extension == ".plod" && parameters.billboards) {
            return Error{label + "`billboards` needs the model mesh; " + parameters.file.string() +
                         " is a .plod (build it with `sylva plant build --bbc`)"};
        }
    }
    if (!parameters.lod.empty()) {
        if (lowerExtension(parameters.lod) != ".plod") {
            return Error{label + parameters.lod.string() + ": `lod` must be a .plod file"};
        }
        if (!std::filesystem::is_regular_file(parameters.lod, error)) {
            return Error{label + parameters.lod.string() + ": file not found"};
        }
    }
    return std::unique_ptr<PlantModelSource>(
        new PlantModelSource(std::move(name), std::move(parameters), label));
}

LeafHabit PlantModelSource::leafHabit() const {
    return parameters_.leafHabit.value_or(Phenology::habitOfPlantPreset(parameters_.preset));
}

Result<std::unique_ptr<Source>> PlantModelSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    PlantModelParameters p;
    if (const Value* preset = reader.value("preset")) {
        const Word* word = preset->get<Word>();
        const std::string* text = preset->get<std::string>();
        p.preset = word != nullptr ? word->text : text != nullptr ? *text : std::string();
    }
    if (std::optional<double> leaves = reader.optionalNumber("leaves")) {
        p.leaves = static_cast<int>(*leaves);
    }
    p.seed = static_cast<std::uint64_t>(reader.optionalNumber("seed").value_or(1.0));
    p.billboards = reader.boolean("billboards", false);
    if (const Value* habit = reader.value("phenology"); habit && habit->get<Word>()) {
        p.leafHabit = Phenology::habitNamed(habit->get<Word>()->text);
    }
    const auto resolve = [&](const std::string& text) {
        std::filesystem::path path(text);
        if (!text.empty() && path.is_relative()) {
            path = context.projectFolder / path;
        }
        return path.lexically_normal();
    };
    p.file = resolve(reader.string("file"));
    p.lod = resolve(reader.string("lod"));
    // Errors at the attribute they concern (the block for preset/file conflicts).
    std::string where = reader.where();
    if (!p.file.empty()) {
        where = reader.where("file");
    } else if (!p.preset.empty()) {
        where = reader.where("preset");
    }
    if (!p.lod.empty() && !p.file.empty() && lowerExtension(p.file) != ".plod" &&
        !std::filesystem::is_regular_file(p.lod)) {
        where = reader.where("lod");
    }
    Result<std::unique_ptr<PlantModelSource>> made =
        make(context.block.name, std::move(p), std::move(where));
    if (!made) {
        return made.error();
    }
    return std::unique_ptr<Source>(std::move(made.value()));
}

Result<TilePointer> PlantModelSource::produce(const TileKey& key, TileProvider&) const {
    return Error{"source '" + name() + "' gives a plant model, which has no raster tile (" +
                 key.toString() + "); reference it from a plants source's `models`"};
}

std::vector<std::filesystem::path> PlantModelSource::files() const {
    std::vector<std::filesystem::path> files;
    if (!parameters_.file.empty()) {
        files.push_back(parameters_.file);
    }
    if (!parameters_.lod.empty()) {
        files.push_back(parameters_.lod);
    }
    return files;
}

const PlantModelSource* PlantModelSource::from(const Source* source) {
    if (source == nullptr || source->output() != PortType::PlantModel) {
        return nullptr;
    }
    return dynamic_cast<const PlantModelSource*>(source);
}

std::filesystem::path PlantModelSource::cacheDirectory() {
    if (const char* directory = std::getenv("SYLVA_CACHE_DIR"); directory && *directory) {
        return directory;
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
        return std::filesystem::path(xdg) / "sylva";
    }
    if (const char* home = std::getenv("HOME"); home && *home) {
        return std::filesystem::path(home) / ".cache" / "sylva";
    }
    std::error_code error;
    return std::filesystem::temp_directory_path(error) / "sylva-cache";
}

std::filesystem::path PlantModelSource::cacheFile() const {
    return cacheDirectory() / "plants" / (hex(contentHash()) + ".plod");
}

Result<std::shared_ptr<const PlantAsset>> PlantModelSource::asset() const {
    std::call_once(once_, [this] { asset_.emplace(build()); });
    return *asset_;
}

Result<std::shared_ptr<const PlantAsset>> PlantModelSource::build() const {
    auto asset = std::make_shared<PlantAsset>();
    asset->name = name();
    const std::string extension = lowerExtension(parameters_.file);

    // The mesh.
    if (extension == ".plod") {
        Result<PlantLod> lod = readPlodFile(parameters_.file.string());
        if (!lod) {
            return Error{where_ + lod.error().message};
        }
        asset->model.name = name();
        asset->lod = std::move(lod.value());
        asset->lod.name = name();
        return std::shared_ptr<const PlantAsset>(std::move(asset));
    }
    if (!parameters_.file.empty()) {
        Result<PlantModel> model = PlantImporter::import(parameters_.file);
        if (!model) {
            return Error{where_ + model.error().message};
        }
        asset->model = std::move(model.value());
    } else {
        Result<TreeParameters> preset = PlantGenerator::preset(parameters_.preset);
        if (!preset) {
            return Error{where_ + preset.error().message};
        }
        PlantGeneratorOptions options;
        options.seed = parameters_.seed;
        options.leafCount = parameters_.leaves;
        Result<PlantModel> model = PlantGenerator::generate(preset.value(), options);
        if (!model) {
            return Error{where_ + model.error().message};
        }
        asset->model = std::move(model.value());
    }

    // The LoD: a given .plod, else the cache, else built (and cached).
    if (!parameters_.lod.empty()) {
        Result<PlantLod> lod = readPlodFile(parameters_.lod.string());
        if (!lod) {
            return Error{where_ + lod.error().message};
        }
        asset->lod = std::move(lod.value());
    } else {
        const std::filesystem::path cache = cacheFile();
        std::error_code error;
        bool cached = false;
        if (std::filesystem::exists(cache, error)) {
            Result<PlantLod> lod = readPlodFile(cache.string());
            if (lod) {
                asset->lod = std::move(lod.value());
                cached = true;
            } else {
                std::fprintf(stderr,
                             "warning: plant_model '%s': ignoring the cached LoD (%s); "
                             "rebuilding\n",
                             name().c_str(), lod.error().message.c_str());
            }
        }
        if (!cached) {
            PlantLodOptions options;
            options.seed = static_cast<std::uint32_t>(parameters_.seed);
            Result<PlantLod> lod = buildPlantLod(asset->model, options);
            if (!lod) {
                return Error{where_ + lod.error().message};
            }
            if (parameters_.billboards) {
                if (Status built = addBillboardClouds(asset->model, lod.value(), options); !built) {
                    return Error{where_ + built.error().message};
                }
            }
            asset->lod = std::move(lod.value());
            asset->lod.name = name();
            std::filesystem::create_directories(cache.parent_path(), error);
            if (Status written = writePlodFile(asset->lod, cache.string()); !written) {
                std::fprintf(stderr, "warning: plant_model '%s': cannot cache the LoD: %s\n",
                             name().c_str(), written.error().message.c_str());
            }
        }
    }
    if (parameters_.billboards && asset->lod.billboards.levels.empty()) {
        PlantLodOptions options;
        options.seed = static_cast<std::uint32_t>(parameters_.seed);
        if (Status built = addBillboardClouds(asset->model, asset->lod, options); !built) {
            return Error{where_ + built.error().message};
        }
    }
    asset->lod.name = name();
    return std::shared_ptr<const PlantAsset>(std::move(asset));
}

}  // namespace sylva
