#include "BuiltInResources.h"

#include <glslang/Public/ResourceLimits.h>

#include <algorithm>
#include <mutex>
#include <sstream>

namespace tidepool {
namespace {

// GLSL ES 1.00 is checked against the built-in limits every ES 2.0 context has (the GLSL ES 1.00
// section 7.4 minimums), not glslang's defaults, which are desktop-sized (32 draw buffers, 80
// texture units): with those, gl_FragData[1] was accepted although an ES 2.0 driver without
// GL_EXT_draw_buffers rejects it (dEQP-GLES2.functional.shaders.fragdata.invalid_assign_to_1).
// `#version 300 es` likewise gets the minimums every ES 3.0 context has (GLSL ES 3.00 §7.3), not
// glslang's defaults: gl_MaxDrawBuffers 4 instead of 32, gl_MaxVertexOutputVectors 16 instead of
// 64, so a shader that only fits a large desktop GPU is not reported as portable.
// The limits both versions name, as GLSL ES lists its built-in constants.
struct EsMinimums {
    int vertex_attribs;
    int vertex_uniform_vectors;
    int vertex_texture_image_units;
    int combined_texture_image_units;
    int texture_image_units;
    int fragment_uniform_vectors;
    int draw_buffers;
};

TBuiltInResource WithMinimums(const EsMinimums& minimums) {
    TBuiltInResource resources = *GetDefaultResources();
    resources.maxVertexAttribs = minimums.vertex_attribs;
    resources.maxVertexUniformVectors = minimums.vertex_uniform_vectors;
    resources.maxVertexTextureImageUnits = minimums.vertex_texture_image_units;
    resources.maxCombinedTextureImageUnits = minimums.combined_texture_image_units;
    resources.maxTextureImageUnits = minimums.texture_image_units;
    resources.maxFragmentUniformVectors = minimums.fragment_uniform_vectors;
    resources.maxDrawBuffers = minimums.draw_buffers;
    return resources;
}

const TBuiltInResource& MinimumsFor(int version) {
    static const TBuiltInResource es300 = [] {
        TBuiltInResource resources = WithMinimums({16, 256, 16, 32, 16, 224, 4});
        resources.maxVertexOutputVectors = 16;
        resources.maxFragmentInputVectors = 15;
        resources.minProgramTexelOffset = -8;
        resources.maxProgramTexelOffset = 7;
        return resources;
    }();
    static const TBuiltInResource es100 = [] {
        TBuiltInResource resources = WithMinimums({8, 128, 0, 8, 8, 16, 1});
        resources.maxVaryingVectors = 8;
        return resources;
    }();
    return version == 300 ? es300 : version == 100 ? es100 : *GetDefaultResources();
}

}  // namespace

TBuiltInResource ResourcesFor(int version, const DeviceLimits* device, bool appendix_a) {
    TBuiltInResource resources = MinimumsFor(version);
    if (device != nullptr && !device->values.empty()) {
        // glslang's own decoder of its configuration format; every name was checked against
        // ResourceLimitNames() when the file was read, so it never reaches the decoder's printf
        // for an unknown name. It tokenises with strtok, which keeps its state in a global.
        static std::mutex strtok_state;
        std::string text = device->Text();
        const std::lock_guard<std::mutex> lock(strtok_state);
        DecodeResourceLimits(&resources, text.data());
    }
    if (appendix_a) {
        // GLSL ES 1.00 Appendix A §4 (for loops only, with a constant-bounded index that the body
        // does not change) and §5 (indexing by constant-index-expressions only, except uniforms
        // in the vertex shader, which glslang's check already leaves alone).
        TLimits& limits = resources.limits;
        limits.nonInductiveForLoops = false;
        limits.whileLoops = false;
        limits.doWhileLoops = false;
        limits.generalUniformIndexing = false;
        limits.generalAttributeMatrixVectorIndexing = false;
        limits.generalVaryingIndexing = false;
        limits.generalSamplerIndexing = false;
        limits.generalVariableIndexing = false;
        limits.generalConstantMatrixVectorIndexing = false;
    }
    return resources;
}

const std::vector<std::string>& ResourceLimitNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list;
        std::istringstream lines(GetDefaultTBuiltInResourceString());
        for (std::string name, value; lines >> name >> value;) {
            list.push_back(name);
        }
        return list;
    }();
    return names;
}

bool IsResourceSwitch(const std::string& name) {
    static const std::vector<std::string> switches = {
            "nonInductiveForLoops",
            "whileLoops",
            "doWhileLoops",
            "generalUniformIndexing",
            "generalAttributeMatrixVectorIndexing",
            "generalVaryingIndexing",
            "generalSamplerIndexing",
            "generalVariableIndexing",
            "generalConstantMatrixVectorIndexing",
    };
    return std::find(switches.begin(), switches.end(), name) != switches.end();
}

}  // namespace tidepool
