// Lookups over the shader feature table.
#include "tidepool/runner/ShaderFeatures.h"

namespace tidepool::runner {

std::optional<ShaderFeature> FeatureFromDefine(std::string_view define) {
    for (const ShaderFeatureInfo& info : kShaderFeatures) {
        if (info.define == define) {
            return info.feature;
        }
    }
    return std::nullopt;
}

std::vector<std::string> DefineNames(std::initializer_list<ShaderFeature> features) {
    std::vector<std::string> names;
    names.reserve(features.size());
    for (ShaderFeature feature : features) {
        names.emplace_back(DefineName(feature));
    }
    return names;
}

}  // namespace tidepool::runner
