#include "sylva/core/seasons/PlantSeasons.h"

#include <algorithm>

#include "sylva/core/image/ColorSpace.h"

namespace sylva {
namespace {

Error locatedAt(const Value& value, SourceLocation* problem, std::string message) {
    if (problem != nullptr) {
        *problem = value.location;
    }
    return Error{std::move(message)};
}

const Value* attributeValue(const Block& block, std::string_view name) {
    const Attribute* attribute = block.find(name);
    return attribute != nullptr && !attribute->value.empty() ? &attribute->value : nullptr;
}

// One "MM-DD" field of a phenology entry.
Status readDay(const std::string& species, const std::string& key, const Value& value,
               std::optional<double>& out, SourceLocation* problem) {
    const std::string* text = value.get<std::string>();
    Result<double> day = text != nullptr
                             ? PlantDate::parseMonthDay(*text)
                             : Result<double>(Error{"a day of the year is written \"04-20\""});
    if (!day) {
        return locatedAt(value, problem,
                         "phenology of '" + species + "': " + key + ": " + day.error().message);
    }
    out = day.value();
    return Status::success();
}

Status readField(PlantSeasons::Override& entry, const std::string& key, const Value& value,
                 SourceLocation* problem) {
    const std::string where = "phenology of '" + entry.species + "': ";
    if (key == "type") {
        const Word* word = value.get<Word>();
        entry.habit = word != nullptr ? Phenology::habitNamed(word->text) : std::nullopt;
        if (!entry.habit) {
            return locatedAt(value, problem, where + "type must be deciduous, evergreen or palm");
        }
        return Status::success();
    }
    if (key == "leaf_out" || key == "full_leaf" || key == "colouring" || key == "leaf_fall") {
        std::optional<double>& day = key == "leaf_out"    ? entry.leafOut
                                     : key == "full_leaf" ? entry.fullLeaf
                                     : key == "colouring" ? entry.colouring
                                                          : entry.leafFall;
        return readDay(entry.species, key, value, day, problem);
    }
    if (key == "winter_leaves") {
        const Quantity* share = value.get<Quantity>();
        if (share == nullptr || share->value < 0.0 || share->value > 1.0) {
            return locatedAt(value, problem, where + "winter_leaves must be within 0% and 100%");
        }
        entry.winterLeaves = share->value;
        return Status::success();
    }
    if (key == "autumn_colour") {
        const Color* colour = value.get<Color>();
        if (colour == nullptr) {
            return locatedAt(value, problem, where + "autumn_colour must be a colour (#B85A1E)");
        }
        entry.autumnColour =
            glm::vec3(srgbToLinear(colour->r), srgbToLinear(colour->g), srgbToLinear(colour->b));
        return Status::success();
    }
    if (key == "tropics") {
        const bool* seasonal = value.get<bool>();
        if (seasonal == nullptr) {
            return locatedAt(value, problem, where + "tropics must be true or false");
        }
        entry.seasonalInTropics = *seasonal;
        return Status::success();
    }
    return locatedAt(value, problem,
                     where + "unknown key '" + key +
                         "' (type, leaf_out, full_leaf, colouring, leaf_fall, winter_leaves, "
                         "autumn_colour, tropics)");
}

Phenology apply(const PlantSeasons::Override& entry, LeafHabit defaultHabit) {
    Phenology table = Phenology::preset(entry.habit.value_or(defaultHabit));
    table.leafOut = entry.leafOut.value_or(table.leafOut);
    table.fullLeaf = entry.fullLeaf.value_or(table.fullLeaf);
    table.colouring = entry.colouring.value_or(table.colouring);
    table.leafFall = entry.leafFall.value_or(table.leafFall);
    table.winterLeaves = entry.winterLeaves.value_or(table.winterLeaves);
    if (entry.autumnColour) {
        table.autumnColour = entry.autumnColour;
    }
    table.seasonalInTropics = entry.seasonalInTropics.value_or(table.seasonalInTropics);
    return table;
}

Result<PlantSeasons::Override> readEntry(const std::string& species, const Value& value,
                                         SourceLocation* problem) {
    PlantSeasons::Override entry;
    entry.species = species;
    entry.location = value.location;
    if (const Word* word = value.get<Word>()) {
        entry.habit = Phenology::habitNamed(word->text);
        if (!entry.habit) {
            return locatedAt(value, problem,
                             "phenology of '" + species +
                                 "': expected deciduous, evergreen, palm or a table { ... }");
        }
        return entry;
    }
    const ValueObject* fields = value.get<ValueObject>();
    if (fields == nullptr) {
        return locatedAt(value, problem,
                         "phenology of '" + species +
                             "': expected deciduous, evergreen, palm or a table { ... }");
    }
    for (const auto& [key, field] : *fields) {
        if (Status read = readField(entry, key, field, problem); !read) {
            return read.error();
        }
    }
    // Days out of order cannot depend on the default habit: the presets share them.
    if (Status valid = apply(entry, LeafHabit::Deciduous).validate(); !valid) {
        return locatedAt(value, problem,
                         "phenology of '" + species + "': " + valid.error().message);
    }
    return entry;
}

Status readPhenology(const Value& value, const std::vector<std::string>& species,
                     std::vector<PlantSeasons::Override>& out, SourceLocation* problem) {
    const ValueObject* table = value.get<ValueObject>();
    if (table == nullptr) {
        return locatedAt(value, problem, "phenology: expected { species = deciduous, ... }");
    }
    for (const auto& [name, entryValue] : *table) {
        if (std::find(species.begin(), species.end(), name) == species.end()) {
            std::string known;
            for (const std::string& s : species) {
                known += (known.empty() ? "" : ", ") + s;
            }
            return locatedAt(entryValue, problem,
                             "phenology names species '" + name +
                                 "', which this block does not "
                                 "have (species: " +
                                 (known.empty() ? std::string("none") : known) + ")");
        }
        Result<PlantSeasons::Override> entry = readEntry(name, entryValue, problem);
        if (!entry) {
            return entry.error();
        }
        out.push_back(std::move(entry.value()));
    }
    return Status::success();
}

}  // namespace

PlantSeasons PlantSeasons::planting(const PlantDate& planted, GrowthCurve growth) {
    PlantSeasons seasons;
    seasons.planted_ = planted;
    seasons.growth_ = std::move(growth);
    return seasons;
}

std::vector<std::string> PlantSeasons::speciesOf(const Block& block) {
    std::vector<std::string> names;
    if (const Value* species = attributeValue(block, "species")) {
        if (const ValueObject* object = species->get<ValueObject>()) {
            for (const auto& [key, value] : *object) {
                names.push_back(key);
            }
        }
    }
    if (const Value* map = attributeValue(block, "species_map")) {
        if (const ValueObject* object = map->get<ValueObject>()) {
            for (const auto& [key, value] : *object) {
                const std::string* text = value.get<std::string>();
                const Word* word = value.get<Word>();
                const std::string name = text ? *text : word ? word->text : std::string();
                if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) {
                    names.push_back(name);
                }
            }
        }
    }
    return names;
}

Result<PlantSeasons> PlantSeasons::read(const Block& block, const std::vector<std::string>& species,
                                        SourceLocation* problem) {
    PlantSeasons seasons;
    const Value* planted = attributeValue(block, "planted");
    if (planted != nullptr) {
        const std::string* text = planted->get<std::string>();
        Result<PlantDate> date = text ? PlantDate::parse(*text)
                                      : Result<PlantDate>(Error{"expected a date (2027-03-01)"});
        if (!date) {
            return locatedAt(*planted, problem, "planted: " + date.error().message);
        }
        seasons.planted_ = date.value();
    }
    if (const Value* growth = attributeValue(block, "growth")) {
        if (planted == nullptr) {
            return locatedAt(*growth, problem,
                             "growth needs `planted` (the date the ages count from)");
        }
        Result<GrowthCurve> curve = GrowthCurve::read(*growth, problem);
        if (!curve) {
            return curve.error();
        }
        seasons.growth_ = std::move(curve.value());
    }
    if (const Value* phenology = attributeValue(block, "phenology")) {
        if (Status read = readPhenology(*phenology, species, seasons.overrides_, problem); !read) {
            return read.error();
        }
    }
    return seasons;
}

Phenology PlantSeasons::phenologyOf(const std::string& species, LeafHabit defaultHabit) const {
    for (const Override& entry : overrides_) {
        if (entry.species == species) {
            return apply(entry, defaultHabit);
        }
    }
    return Phenology::preset(defaultHabit);
}

std::optional<GrowthScale> PlantSeasons::scaleAt(const PlantDate& date, double modelHeight) const {
    if (!planted_) {
        return GrowthScale{};
    }
    return growth_.at(date.yearsSince(*planted_), modelHeight);
}

}  // namespace sylva
