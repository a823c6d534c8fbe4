// The resource limits glslang checks a stage against (compiler/src/BuiltInResources.h): the
// GLSL ES minimums per version, a device's values in their place, and WebGL 1's Appendix A.
#include "tidepool/DeviceLimits.h"

#include <glslang/Include/ResourceLimits.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "BuiltInResources.h"

namespace tidepool {
namespace {

TEST(BuiltInResourcesTest, EachEsVersionGetsTheMinimumsOfItsSpecificationNotDesktopDefaults) {
    // GLSL ES 1.00 §7.4.
    const TBuiltInResource es100 = ResourcesFor(100, nullptr, false);
    EXPECT_EQ(es100.maxVertexAttribs, 8);
    EXPECT_EQ(es100.maxVertexUniformVectors, 128);
    EXPECT_EQ(es100.maxVaryingVectors, 8);
    EXPECT_EQ(es100.maxVertexTextureImageUnits, 0);
    EXPECT_EQ(es100.maxFragmentUniformVectors, 16);
    EXPECT_EQ(es100.maxDrawBuffers, 1);
    // GLSL ES 3.00 §7.3.
    const TBuiltInResource es300 = ResourcesFor(300, nullptr, false);
    EXPECT_EQ(es300.maxVertexAttribs, 16);
    EXPECT_EQ(es300.maxFragmentUniformVectors, 224);
    EXPECT_EQ(es300.maxDrawBuffers, 4);
    EXPECT_EQ(es300.maxVertexOutputVectors, 16);
    EXPECT_EQ(es300.minProgramTexelOffset, -8);
    EXPECT_EQ(es300.maxProgramTexelOffset, 7);
    // Any other version keeps glslang's defaults, which are larger.
    EXPECT_GT(ResourcesFor(310, nullptr, false).maxDrawBuffers, 4);
}

TEST(BuiltInResourcesTest, DeviceValuesReplaceTheMinimumsAndLeaveTheRest) {
    const DeviceLimitsRead read =
            ParseDeviceLimits("MaxFragmentUniformVectors 64\nMaxDrawBuffers 8\n", "phone.conf");
    ASSERT_TRUE(read.ok);
    const TBuiltInResource resources = ResourcesFor(100, &read.limits, false);
    EXPECT_EQ(resources.maxFragmentUniformVectors, 64);
    EXPECT_EQ(resources.maxDrawBuffers, 8);
    EXPECT_EQ(resources.maxVertexUniformVectors, 128);  // not in the file: the ES minimum
    // An empty device changes nothing.
    const DeviceLimits none;
    EXPECT_EQ(ResourcesFor(100, &none, false).maxFragmentUniformVectors, 16);
}

TEST(BuiltInResourcesTest, AppendixATurnsOffGeneralLoopsAndIndexingOnly) {
    const TLimits plain = ResourcesFor(100, nullptr, false).limits;
    EXPECT_TRUE(plain.whileLoops);
    EXPECT_TRUE(plain.generalVariableIndexing);
    const TBuiltInResource webgl = ResourcesFor(100, nullptr, true);
    const TLimits& limits = webgl.limits;
    EXPECT_FALSE(limits.nonInductiveForLoops);
    EXPECT_FALSE(limits.whileLoops);
    EXPECT_FALSE(limits.doWhileLoops);
    EXPECT_FALSE(limits.generalUniformIndexing);
    EXPECT_FALSE(limits.generalAttributeMatrixVectorIndexing);
    EXPECT_FALSE(limits.generalVaryingIndexing);
    EXPECT_FALSE(limits.generalSamplerIndexing);
    EXPECT_FALSE(limits.generalVariableIndexing);
    EXPECT_FALSE(limits.generalConstantMatrixVectorIndexing);
    EXPECT_EQ(webgl.maxFragmentUniformVectors, 16);  // the numeric limits are untouched
}

TEST(BuiltInResourcesTest, LimitNamesAreGlslangsAndOnlyTheLoopAndIndexingOnesAreSwitches) {
    const std::vector<std::string>& names = ResourceLimitNames();
    ASSERT_FALSE(names.empty());
    EXPECT_EQ(names.front(), "MaxLights");  // the order `glslangValidator -c` prints
    for (const char* name : {"MaxDrawBuffers", "MaxFragmentUniformVectors", "whileLoops",
                             "generalConstantMatrixVectorIndexing"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    }
    std::size_t switches = 0;
    for (const std::string& name : names) {
        switches += IsResourceSwitch(name) ? 1U : 0U;
    }
    EXPECT_EQ(switches, 9U);
    EXPECT_TRUE(IsResourceSwitch("nonInductiveForLoops"));
    EXPECT_FALSE(IsResourceSwitch("MaxDrawBuffers"));
    EXPECT_FALSE(IsResourceSwitch("whileloops"));
}

}  // namespace
}  // namespace tidepool
