// The whitepaper's rows as frame plans: for each row, the renderer's own plan of its two arms
// (passes, targets, clips, clears, every draw and its program) differs only in the change the
// whitepaper's sentence makes. Each test undoes the declared change on the candidate and expects
// the baseline back, at every default view, so any other difference fails it.
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/runner/FramePlan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace tidepool::runner {
namespace {

// One draw: the program's name, its defines (for water_uniform the effects its bools switch
// on) and what it draws.
struct Draw {
    std::string program;
    std::vector<std::string> defines;
    std::string what;
    bool operator==(const Draw& o) const {
        return program == o.program && defines == o.defines && what == o.what;
    }
};

struct Pass {
    std::string name;
    int width = 0;
    int height = 0;
    std::string clip;  // "oblique", "discard" or "none"
    glm::vec4 clear{0.0F};
    std::vector<Draw> draws;
    bool operator==(const Pass& o) const {
        return name == o.name && width == o.width && height == o.height && clip == o.clip &&
               clear == o.clear && draws == o.draws;
    }
};

struct Frame {
    float wave_distortion = 0.0F;
    std::vector<Pass> passes;
    bool operator==(const Frame& o) const {
        return wave_distortion == o.wave_distortion && passes == o.passes;
    }
    Pass* Find(const std::string& name) {
        auto found = std::find_if(passes.begin(), passes.end(),
                                  [&](const Pass& p) { return p.name == name; });
        return found == passes.end() ? nullptr : &*found;
    }
};

std::ostream& operator<<(std::ostream& out, const Frame& frame) {
    out << "wave_distortion " << frame.wave_distortion << "\n";
    for (const Pass& pass : frame.passes) {
        out << pass.name << " " << pass.width << "x" << pass.height << " clip " << pass.clip
            << " clear " << pass.clear.r << "," << pass.clear.g << "," << pass.clear.b << ","
            << pass.clear.a << "\n";
        for (const Draw& draw : pass.draws) {
            out << "  " << draw.program << ":";
            for (const std::string& d : draw.defines) {
                out << d << ",";
            }
            out << " " << draw.what << "\n";
        }
    }
    return out;
}

Frame Describe(const FramePlan& plan, const RenderConfiguration& c, const Scene& scene) {
    Frame frame;
    frame.wave_distortion = plan.wave_distortion;
    for (const PassPlan& p : plan.passes) {
        Pass pass;
        pass.name = PassName(p.kind);
        pass.width = p.width;
        pass.height = p.height;
        pass.clip = p.clip_oblique ? "oblique" : p.clip_discard ? "discard" : "none";
        pass.clear = p.clear_colour;
        if (p.draw_sky) {
            pass.draws.push_back({p.sky_program.program, p.sky_program.defines, "sky"});
        }
        for (int mesh : p.meshes) {
            pass.draws.push_back({p.model_program.program, p.model_program.defines,
                                  mesh < 0 ? scene.terrain.name
                                           : scene.objects[static_cast<std::size_t>(mesh)].name});
        }
        if (p.draw_water) {
            const bool uniform = p.water_program.program == kWaterUniformProgram;
            pass.draws.push_back({p.water_program.program,
                                  uniform ? c.effects : p.water_program.defines, "water"});
        }
        frame.passes.push_back(std::move(pass));
    }
    return frame;
}

// Removes `define` from every draw of `program` (in `pass` only, when given).
void RemoveDefine(Frame* frame, const std::string& program, const std::string& define,
                  const std::string& pass_name = "") {
    for (Pass& pass : frame->passes) {
        if (!pass_name.empty() && pass.name != pass_name) {
            continue;
        }
        for (Draw& draw : pass.draws) {
            if (draw.program == program) {
                draw.defines.erase(std::remove(draw.defines.begin(), draw.defines.end(), define),
                                   draw.defines.end());
            }
        }
    }
}

void AddDefine(Frame* frame, const std::string& program, const std::string& define,
               const std::string& pass_name) {
    for (Pass& pass : frame->passes) {
        for (Draw& draw : pass.draws) {
            if (pass.name == pass_name && draw.program == program) {
                draw.defines = MakeVariant(program,
                                           [&] {
                                               std::vector<std::string> d = draw.defines;
                                               d.push_back(define);
                                               return d;
                                           }())
                                       .defines;
            }
        }
    }
}

void RemovePass(Frame* frame, const std::string& name) {
    frame->passes.erase(std::remove_if(frame->passes.begin(), frame->passes.end(),
                                       [&](const Pass& p) { return p.name == name; }),
                        frame->passes.end());
}

class FramePlanTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        ConfigResult loaded =
                LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
        ASSERT_TRUE(loaded.config.has_value());
        config_ = new VariantConfig(std::move(*loaded.config));
        variants_ = new std::vector<Variant>(
                ExpandVariants(*config_, ExpansionOptions{config_->max_variants}).variants);
        configurations_ = new ConfigurationSet(BuildDefaultConfigurations(*config_, *variants_));
        scene_ = new Scene(BuildDefaultScene());
    }
    static void TearDownTestSuite() {
        delete config_;
        delete variants_;
        delete configurations_;
        delete scene_;
    }

    static const RenderConfiguration& Preset(const std::string& name) {
        for (const RenderConfiguration& c : configurations_->configurations) {
            if (std::find(c.presets.begin(), c.presets.end(), name) != c.presets.end()) {
                return c;
            }
        }
        ADD_FAILURE() << "no preset " << name;
        return configurations_->configurations.front();
    }

    static Frame Plan(const RenderConfiguration& c, const CameraView& view) {
        return Describe(PlanFrame(c, settings_, *scene_, view), c, *scene_);
    }

    // For every default view: `undo` applied to the candidate's frame gives the baseline's, and
    // the two frames differ before it (the row changes something).
    template <typename Undo>
    static void ExpectOnlyChange(const std::string& baseline, const std::string& candidate,
                                 Undo undo) {
        for (const CameraView& view : DefaultViews()) {
            const Frame base = Plan(Preset(baseline), view);
            Frame changed = Plan(Preset(candidate), view);
            EXPECT_FALSE(changed == base) << view.name << ": the arms plan the same frame";
            undo(&changed, base);
            EXPECT_TRUE(changed == base)
                    << view.name << "\nbaseline " << baseline << ":\n"
                    << base << "candidate " << candidate << " with the change undone:\n"
                    << changed;
        }
    }

    static inline VariantConfig* config_ = nullptr;
    static inline std::vector<Variant>* variants_ = nullptr;
    static inline ConfigurationSet* configurations_ = nullptr;
    static inline Scene* scene_ = nullptr;
    static inline const RenderSettings settings_{};
};

TEST_F(FramePlanTest, Row1AddsTheRefractionPassToTheBumpedReflection) {
    EXPECT_EQ(Preset("reflection_only").effects, std::vector<std::string>{"ENABLE_DISTORTION"});
    ExpectOnlyChange("reflection_only", "reflection_refraction", [](Frame* f, const Frame&) {
        ASSERT_NE(f->Find("refraction"), nullptr);
        RemovePass(f, "refraction");
        RemoveDefine(f, "water", "ENABLE_REFRACTION");
    });
}

TEST_F(FramePlanTest, Row2MixesTheWaterColourOnly) {
    ExpectOnlyChange("reflection_only", "reflection_water_colour", [](Frame* f, const Frame&) {
        RemoveDefine(f, "water", "ENABLE_WATER_COLOUR");
    });
}

TEST_F(FramePlanTest, Row3BlendsTheWaterOnly) {
    ExpectOnlyChange("reflection_only", "reflection_alpha_blend", [](Frame* f, const Frame&) {
        RemoveDefine(f, "water", "ENABLE_ALPHA_BLEND");
    });
}

TEST_F(FramePlanTest, Row4DropsOnlyTheModelsDepthFog) {
    // Water fog, sky fog, the refraction's clear colour and its omitted sky stay.
    ExpectOnlyChange("full", "full_no_fog", [](Frame* f, const Frame&) {
        AddDefine(f, "model", "ENABLE_FOG_DEPTH", "refraction");
    });
}

TEST_F(FramePlanTest, Row5AddsOnlyTheFresnelDefine) {
    ExpectOnlyChange("full_constant_mix", "full",
                     [](Frame* f, const Frame&) { RemoveDefine(f, "water", "ENABLE_FRESNEL"); });
}

TEST_F(FramePlanTest, Row6DividesByTheEyeDistanceWithTheSameOffsetAtTheTypicalDistance) {
    ExpectOnlyChange("full_unscaled_distortion", "full", [](Frame* f, const Frame& base) {
        RemoveDefine(f, "water", "ENABLE_SCALE_DISTORTION");
        // Scaled: the demo's 100, divided per fragment; unscaled: 100 over the typical distance.
        EXPECT_EQ(f->wave_distortion, RenderSettings{}.wave_distortion);
        EXPECT_LT(base.wave_distortion, f->wave_distortion);
        f->wave_distortion = base.wave_distortion;
    });
    for (const CameraView& view : DefaultViews()) {
        const float unscaled = Plan(Preset("full_unscaled_distortion"), view).wave_distortion;
        EXPECT_FLOAT_EQ(unscaled * TypicalWaterDistance(view, scene_->water_height),
                        RenderSettings{}.wave_distortion)
                << view.name;
    }
}

TEST_F(FramePlanTest, Row7DoesTheSameWaterWorkAtTheDemoResolutionBehindTheGround) {
    ExpectOnlyChange("full", "full_low_res_water", [](Frame* f, const Frame& base) {
        const Pass* low_res = f->Find("low_res_water");
        ASSERT_NE(low_res, nullptr);
        EXPECT_EQ(low_res->width, 256);  // the demo's size at 640x480
        EXPECT_EQ(low_res->height, 256);
        // The ground first, with the main pass's program, then the same water program.
        const Pass* main = f->Find("main");
        ASSERT_EQ(low_res->draws.size(), 2U);
        EXPECT_EQ(low_res->draws[0], (Draw{"model", main->draws[1].defines, "terrain"}));
        EXPECT_EQ(low_res->draws[1], base.passes.back().draws.back());
        // Fogged water reaches the fog colour at the far plane: no fringe at the horizon.
        EXPECT_EQ(low_res->clear, glm::vec4(RenderSettings{}.fog_colour, 1.0F));
        RemovePass(f, "low_res_water");
        Draw& composite = f->passes.back().draws.back();
        EXPECT_EQ(composite.program, "water_composite");
        composite = base.passes.back().draws.back();
    });
}

TEST_F(FramePlanTest, Row8NormalisesThroughTheDemosCubeMapOnly) {
    EXPECT_EQ(RenderSettings{}.normalisation_cube_size, 8);
    ExpectOnlyChange("full", "full_cubemap_normalise",
                     [](Frame* f, const Frame&) { RemoveDefine(f, "water", "NORMALISE_CUBEMAP"); });
}

TEST_F(FramePlanTest, Row9SwitchesTheSameEffectsByUniformBools) {
    ExpectOnlyChange("full_uniform_bools", "full", [](Frame* f, const Frame&) {
        for (Pass& pass : f->passes) {
            for (Draw& draw : pass.draws) {
                if (draw.program == "water") {
                    draw.program = std::string(kWaterUniformProgram);
                }
            }
        }
    });
}

TEST_F(FramePlanTest, Row10ClipsTheModelsByDiscardAndDrawsTheSkyAsBefore) {
    ExpectOnlyChange("full", "full_clip_discard", [](Frame* f, const Frame&) {
        for (Pass& pass : f->passes) {
            if (pass.clip == "discard") {
                pass.clip = "oblique";
            }
        }
        RemoveDefine(f, "model", "CLIP_DISCARD");
    });
}

TEST_F(FramePlanTest, Row11HalvesTheReflectionAlone) {
    ExpectOnlyChange("full", "full_reflection_128", [](Frame* f, const Frame&) {
        Pass* reflection = f->Find("reflection");
        ASSERT_NE(reflection, nullptr);
        EXPECT_EQ(reflection->width, 128);
        EXPECT_EQ(f->Find("refraction")->width, 256);
        reflection->width = reflection->height = 256;
    });
}

TEST_F(FramePlanTest, EveryProgramAFrameDrawsIsInTheValidatedMatrix) {
    std::set<std::string> validated;
    for (const Variant& v : *variants_) {
        validated.insert(v.Id());
    }
    for (const RenderConfiguration& c : configurations_->configurations) {
        for (const CameraView& view : DefaultViews()) {
            for (const PassPlan& pass : PlanFrame(c, settings_, *scene_, view).passes) {
                for (const Variant* program :
                     {&pass.sky_program, &pass.model_program, &pass.water_program}) {
                    if (!program->program.empty()) {
                        EXPECT_TRUE(validated.count(program->Id()))
                                << program->Id() << " in " << c.id << " at " << view.name;
                    }
                }
            }
        }
        // The oblique projection's fallback clips the models by discard: those variants too.
        RenderConfiguration discard = c;
        discard.passes.clip = "discard";
        const std::vector<const RenderConfiguration*> arms = {&c, &discard};
        for (const RenderConfiguration* arm : arms) {
            for (const Variant& helper : HelperPrograms(*arm)) {
                EXPECT_TRUE(validated.count(helper.Id())) << helper.Id() << " for " << c.id;
            }
        }
    }
}

TEST_F(FramePlanTest, TargetsFollowTheDemosRuleForTheWindow) {
    EXPECT_EQ(DemoTargetSize(640, 480), 256);
    EXPECT_EQ(DemoTargetSize(320, 240), 128);
    EXPECT_EQ(DemoTargetSize(160, 120), 64);
    EXPECT_EQ(DemoTargetSize(512, 512), 512);
    RenderSettings small;
    small.width = 320;
    small.height = 240;
    EXPECT_EQ(LowResWaterSize(small), 128);
    small.low_res_water_size = 32;
    EXPECT_EQ(LowResWaterSize(small), 32);
}

// Reflection and refraction follow the window unless a pass option sets them (whitepaper row 11's
// 128 and the reference's 512 stay what variants.yaml says at every window size).
TEST_F(FramePlanTest, ReflectionAndRefractionFollowTheWindowUnlessAPassOptionSetsThem) {
    auto pass_width = [&](const RenderConfiguration& c, int width, int height, const char* name) {
        RenderSettings settings = settings_;
        settings.width = width;
        settings.height = height;
        for (const PassPlan& pass :
             PlanFrame(c, settings, *scene_, DefaultViews().front()).passes) {
            if (PassName(pass.kind) == std::string_view(name)) {
                return pass.width;
            }
        }
        return -1;
    };
    const RenderConfiguration& full = Preset("full");
    EXPECT_EQ(pass_width(full, 640, 480, "reflection"), 256);
    EXPECT_EQ(pass_width(full, 640, 480, "refraction"), 256);
    EXPECT_EQ(pass_width(full, 320, 240, "reflection"), 128);
    EXPECT_EQ(pass_width(full, 320, 240, "refraction"), 128);
    EXPECT_EQ(pass_width(full, 1280, 720, "reflection"), 512);
    const RenderConfiguration& row11 = Preset("full_reflection_128");
    EXPECT_EQ(pass_width(row11, 320, 240, "reflection"), 128);
    EXPECT_EQ(pass_width(row11, 1280, 720, "reflection"), 128);
    EXPECT_EQ(pass_width(row11, 1280, 720, "refraction"), 512);
    const RenderConfiguration& reference = Preset("reference");
    EXPECT_EQ(pass_width(reference, 320, 240, "refraction"), 512);
}

}  // namespace
}  // namespace tidepool::runner
