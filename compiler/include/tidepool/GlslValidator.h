// Validation of variants (and of plain shader files) as GLSL ES with glslang used as a library:
// every distinct stage program is parsed once, every program is linked.
#pragma once

#include "tidepool/DeviceLimits.h"
#include "tidepool/Diagnostic.h"
#include "tidepool/SourceAssembler.h"
#include "tidepool/StaticCost.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/ContentCache.h"
#include "tidepool/base/CpuPlacement.h"

#include <array>
#include <atomic>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace tidepool {

/// glslang's built-in symbol tables for some targets, built on a second thread from construction
/// on, so that worker processes forked after Finish() inherit them instead of each building them
/// again. A caller who knows glslang will run (its cache holds nothing) starts one before loading
/// its configuration and hands it to ValidateVariants (ValidationOptions::warm_up).
class GlslangWarmUp {
public:
    explicit GlslangWarmUp(std::vector<GlslTarget> targets);
    GlslangWarmUp(const GlslangWarmUp&) = delete;  // the thread holds `this`
    GlslangWarmUp& operator=(const GlslangWarmUp&) = delete;
    /// Waits for the thread (a fork must see one thread); the targets it was given. A warm-up
    /// that failed costs time only: each worker then builds the tables it needs. Idempotent.
    const std::vector<GlslTarget>& Finish();

private:
    std::vector<GlslTarget> targets_;
    base::CpuPlacement placement_;     // the thread starts on another CPU than its creator's
    std::atomic<bool> placed_{false};  // the thread has been placed there
    std::jthread thread_;              // last: it reads the above, and is joined before they go
};

/// How to validate.
struct ValidationOptions {
    int jobs = 1;  // worker threads
    std::vector<GlslTarget> targets = {GlslTarget::kEs100};
    /// Where stage and link results are looked up before glslang runs and stored after, keyed
    /// by the stage's source as glslang receives it (file text and the defines it names),
    /// file name, stage, target, glslang's version and resource limits and tidepool's
    /// validation code; none: no cache. Not owned; its Stats() say what it did.
    base::ContentCache* cache = nullptr;
    /// A device's limits, checked instead of the GLSL ES minimums; none: the minimums. Not owned.
    const DeviceLimits* limits = nullptr;
    /// A warm-up the caller started, finished before the first fork; none: validation starts its
    /// own when the cache cannot answer everything. Not owned.
    GlslangWarmUp* warm_up = nullptr;
    /// Whether each valid stage program gets its StaticCost (the manifest's costs); without, its
    /// `cost` may stay empty, which spares the analysis when nothing will show it. A cached stage
    /// without a cost does not answer a validation that wants one: it is parsed again.
    bool static_costs = true;
};

/// One distinct stage program: all variants whose preprocessed stage source is identical share it.
struct StageProgram {
    Stage stage = Stage::kVertex;
    GlslTarget target = GlslTarget::kEs100;
    std::string file;  // as the user named it
    /// 16 hex digits: of a SHA-256 over what decides the preprocessed text (DefineRelevance), or
    /// of a 64-bit FNV-1a over the text itself where that walk does not follow the file (over the
    /// file's own text in plain-file validation).
    std::string hash;
    std::vector<std::string> defines;   // the defines of the first variant that produced it
    std::vector<std::string> variants;  // ids of every variant that uses it
    bool valid = false;
    std::vector<Diagnostic> diagnostics;
    StageCost cost;
};

/// What one step of a variant's validation (a stage's parse, or the link) came to. kNotRun: the
/// step had nothing to work on (the link after a failed stage; a stage plain-file mode lacks).
enum class StepStatus { kNotRun, kValid, kInvalid };

/// "not run", "valid" or "invalid".
const char* StepStatusName(StepStatus status);

/// One step of a variant's validation with the messages it produced, so that a CI report can say
/// which stage failed and file each message under it.
struct StepVerdict {
    StepStatus status = StepStatus::kNotRun;
    std::vector<Diagnostic> diagnostics;  // tagged with the variant's id
};

/// The verdict on one variant for one target: both stages and the link.
struct VariantVerdict {
    Variant variant;
    GlslTarget target = GlslTarget::kEs100;
    std::string vertex_hash;
    std::string fragment_hash;
    bool valid = false;
    std::vector<Diagnostic> diagnostics;  // stage and link messages, tagged with this variant's id
    StepVerdict vertex;                   // the same messages, step by step
    StepVerdict fragment;
    StepVerdict link;

    /// The three steps by name ("vertex", "fragment", "link"), in that order.
    std::array<std::pair<const char*, const StepVerdict*>, 3> NamedSteps() const {
        return {{{"vertex", &vertex}, {"fragment", &fragment}, {"link", &link}}};
    }
};

/// Everything validation found.
struct ValidationReport {
    std::vector<VariantVerdict> verdicts;      // in the order of the variants given, per target
    std::vector<StageProgram> stage_programs;  // distinct programs, vertex and fragment
    int stage_slots = 0;                       // variants × targets × 2 stages
    int links = 0;                             // distinct (vertex, fragment) pairs linked
    std::vector<Diagnostic> diagnostics;       // problems not tied to a variant (unreadable files)
    /// glslang crashed, timed out or ran out of memory on some stage or link: an "internal
    /// compiler error" stands where another run may find a verdict.
    bool internal_errors = false;

    /// How many stage slots reused a program another variant already had.
    int SharedStageSlots() const { return stage_slots - static_cast<int>(stage_programs.size()); }
    /// Number of verdicts that are invalid.
    int InvalidCount() const;
    /// The verdict on `variant` for `target`; nullptr when the report has none.
    const VariantVerdict* Find(const Variant& variant, GlslTarget target) const;
};

/// Validates every variant of `config` for every target in `options`; stage errors and link
/// errors become diagnostics at the user's file and line, tagged with the variant id. Fails only
/// through its diagnostics (an unreadable shader file makes the variants using it invalid).
ValidationReport ValidateVariants(const VariantConfig& config, const std::vector<Variant>& variants,
                                  const ValidationOptions& options);

/// The same, but a verdict `known` already holds for a variant and target is taken from it (a
/// run's later stages reuse the validation its manifest came from, built with the same config):
/// only the variants it lacks are validated. The verdicts come in the order of `variants`, per
/// target; stage programs, slots and links count only what was validated here.
ValidationReport ValidateVariants(const VariantConfig& config, const std::vector<Variant>& variants,
                                  const ValidationOptions& options, const ValidationReport& known);

/// A shader file named on the command line.
struct ShaderFile {
    std::string path;
    Stage stage = Stage::kVertex;
};

/// How plain shader files are validated.
struct ShaderFileOptions {
    /// kWebGl1 or kWebGl2: the WebGL rules on top of GLSL ES for the file's own `#version`
    /// (webgl1 runs 100 only; webgl2 runs 100, with the rules WebGL gives 1.00 shaders, and
    /// 300 es); none: GLSL ES only.
    std::optional<GlslTarget> target;
    /// A device's limits, checked instead of the GLSL ES minimums; none: the minimums. Not owned.
    const DeviceLimits* limits = nullptr;
    /// As ValidationOptions::cache: each file's result and the link's are looked up before
    /// glslang runs and stored after; none: no cache. Not owned.
    base::ContentCache* cache = nullptr;
};

/// Validates plain shader files: each is parsed (the GLSL ES version comes from its own `#version`
/// line, 100 when it has none; a desktop version is an error) and, when a vertex and a fragment
/// file are given, the two are linked. Each file is one "variant" named after the file.
ValidationReport ValidateShaderFiles(const std::vector<ShaderFile>& files,
                                     const std::vector<std::string>& defines,
                                     const ShaderFileOptions& options = {});

/// The digest every validation cache key starts from: tidepool's validation code, glslang's
/// version and its default resource limits. Never fails.
const std::string& ValidationCacheIdentity();

/// The stage a file's extension implies (.vert/.vsh → vertex, .frag/.fsh → fragment); false when
/// the extension says nothing.
bool StageFromExtension(const std::string& path, Stage* stage);

}  // namespace tidepool
