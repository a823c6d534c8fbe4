// Static cost analysis. Each reachable function body is walked once (with a TIntermTraverser for
// the counts and a recursive function for the path costs) and the results are combined per call
// site, so a helper called from ten places is inlined ten times in the numbers but walked once.
#include "StaticCostAnalyzer.h"

#include <glslang/Include/PoolAlloc.h>
#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstring>
#include <iterator>
#include <set>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace tidepool {
namespace {

// glslang's name for main() in call and definition nodes (names are mangled with parameter types).
constexpr const char* kMainName = "main(";

// Inlining multiplies a helper's cost by its number of call paths, so a pathological shader could
// overflow an int; costs saturate instead.
int AddCapped(int a, int b) {
    const long long sum = static_cast<long long>(a) + static_cast<long long>(b);
    return static_cast<int>(std::min<long long>(sum, INT_MAX));
}

enum class OpKind { kFree, kArithmetic, kBuiltin, kTextureSample };

// What one operator node costs, and the GLSL name to count it under when it is a call.
struct OpClass {
    OpKind kind = OpKind::kFree;
    std::string name;
};

// One texture operator: its GLSL ES 3.00 name, and the part of the GLSL ES 1.00 name that follows
// the sampler type ("Proj" in texture2DProj); null when GLSL ES 1.00 has no such lookup.
struct TextureOpName {
    glslang::TOperator op;
    const char* es300_name;
    const char* es100_suffix;
};

constexpr TextureOpName kTextureOpNames[] = {
        {glslang::EOpTexture, "texture", ""},
        {glslang::EOpTextureProj, "textureProj", "Proj"},
        {glslang::EOpTextureLod, "textureLod", "Lod"},
        {glslang::EOpTextureProjLod, "textureProjLod", "ProjLod"},
        {glslang::EOpTextureGrad, "textureGrad", "Grad"},
        {glslang::EOpTextureProjGrad, "textureProjGrad", "ProjGrad"},
        {glslang::EOpTextureOffset, "textureOffset", nullptr},
        {glslang::EOpTextureFetch, "texelFetch", nullptr},
        {glslang::EOpTextureFetchOffset, "texelFetchOffset", nullptr},
        {glslang::EOpTextureProjOffset, "textureProjOffset", nullptr},
        {glslang::EOpTextureLodOffset, "textureLodOffset", nullptr},
        {glslang::EOpTextureProjLodOffset, "textureProjLodOffset", nullptr},
        {glslang::EOpTextureGradOffset, "textureGradOffset", nullptr},
        {glslang::EOpTextureProjGradOffset, "textureProjGradOffset", nullptr},
        {glslang::EOpTextureGather, "textureGather", nullptr},
        {glslang::EOpTextureGatherOffset, "textureGatherOffset", nullptr},
        {glslang::EOpTextureGatherOffsets, "textureGatherOffsets", nullptr},
};

// glslang maps texture2D and textureCube alike to EOpTexture, so the GLSL ES 1.00 name is put
// back together from the operator, the sampler argument's type and the stage.
std::string TextureCallName(const glslang::TIntermOperator& node, EShLanguage stage, int version) {
    const glslang::TOperator op = node.getOp();
    const auto* row = std::find_if(std::begin(kTextureOpNames), std::end(kTextureOpNames),
                                   [op](const TextureOpName& entry) { return entry.op == op; });
    if (row == std::end(kTextureOpNames)) {
        return "texture_op_" + std::to_string(static_cast<int>(op));
    }
    if (version >= 300 || row->es100_suffix == nullptr) {
        return row->es300_name;
    }
    // texture2D, textureCube, texture3D (OES_texture_3D), shadow2DEXT (EXT_shadow_samplers).
    const glslang::TIntermAggregate* call = node.getAsAggregate();
    const glslang::TIntermTyped* sampler_arg = call != nullptr && !call->getSequence().empty()
                                                       ? call->getSequence()[0]->getAsTyped()
                                                       : nullptr;
    std::string name = "texture2D";
    bool extension = false;
    if (sampler_arg != nullptr && sampler_arg->getBasicType() == glslang::EbtSampler) {
        const glslang::TSampler& sampler = sampler_arg->getType().getSampler();
        if (sampler.shadow) {
            name = "shadow2D";
            extension = true;
        } else if (sampler.dim == glslang::EsdCube) {
            name = "textureCube";
        } else if (sampler.dim == glslang::Esd3D) {
            name = "texture3D";
        }
    }
    name += row->es100_suffix;
    // In fragment shaders the explicit-LOD and gradient lookups exist only through
    // EXT_shader_texture_lod, whose functions carry the EXT suffix.
    const bool lod_or_grad = op == glslang::EOpTextureLod || op == glslang::EOpTextureProjLod ||
                             op == glslang::EOpTextureGrad || op == glslang::EOpTextureProjGrad;
    if (extension || (lod_or_grad && stage == EShLangFragment)) {
        name += "EXT";
    }
    return name;
}

// A built-in function glslang turns into an operator, and its GLSL name.
struct BuiltinOpName {
    glslang::TOperator op;
    const char* name;
};

// Built-ins that share an operator with a syntactic operator (matrixCompMult is EOpMul, lessThan
// is EOpLessThan). glslang builds calls with two or more arguments as aggregate nodes and the
// operators as binary nodes, so these names apply to aggregates only.
constexpr BuiltinOpName kAggregateBuiltinNames[] = {
        {glslang::EOpMul, "matrixCompMult"},
        {glslang::EOpMod, "mod"},
        {glslang::EOpLessThan, "lessThan"},
        {glslang::EOpGreaterThan, "greaterThan"},
        {glslang::EOpLessThanEqual, "lessThanEqual"},
        {glslang::EOpGreaterThanEqual, "greaterThanEqual"},
        {glslang::EOpEqual, "equal"},
        {glslang::EOpVectorEqual, "equal"},
        {glslang::EOpNotEqual, "notEqual"},
        {glslang::EOpVectorNotEqual, "notEqual"},
};

// Built-ins whose operator is theirs alone: GLSL ES 1.00, OES_standard_derivatives, and the
// GLSL ES 3.00 additions.
constexpr BuiltinOpName kBuiltinNames[] = {
        {glslang::EOpRadians, "radians"},
        {glslang::EOpDegrees, "degrees"},
        {glslang::EOpSin, "sin"},
        {glslang::EOpCos, "cos"},
        {glslang::EOpTan, "tan"},
        {glslang::EOpAsin, "asin"},
        {glslang::EOpAcos, "acos"},
        {glslang::EOpAtan, "atan"},
        {glslang::EOpSinh, "sinh"},
        {glslang::EOpCosh, "cosh"},
        {glslang::EOpTanh, "tanh"},
        {glslang::EOpAsinh, "asinh"},
        {glslang::EOpAcosh, "acosh"},
        {glslang::EOpAtanh, "atanh"},
        {glslang::EOpPow, "pow"},
        {glslang::EOpExp, "exp"},
        {glslang::EOpLog, "log"},
        {glslang::EOpExp2, "exp2"},
        {glslang::EOpLog2, "log2"},
        {glslang::EOpSqrt, "sqrt"},
        {glslang::EOpInverseSqrt, "inversesqrt"},
        {glslang::EOpAbs, "abs"},
        {glslang::EOpSign, "sign"},
        {glslang::EOpFloor, "floor"},
        {glslang::EOpTrunc, "trunc"},
        {glslang::EOpRound, "round"},
        {glslang::EOpRoundEven, "roundEven"},
        {glslang::EOpCeil, "ceil"},
        {glslang::EOpFract, "fract"},
        {glslang::EOpModf, "modf"},
        {glslang::EOpMin, "min"},
        {glslang::EOpMax, "max"},
        {glslang::EOpClamp, "clamp"},
        {glslang::EOpMix, "mix"},
        {glslang::EOpStep, "step"},
        {glslang::EOpSmoothStep, "smoothstep"},
        {glslang::EOpIsNan, "isnan"},
        {glslang::EOpIsInf, "isinf"},
        {glslang::EOpFloatBitsToInt, "floatBitsToInt"},
        {glslang::EOpFloatBitsToUint, "floatBitsToUint"},
        {glslang::EOpIntBitsToFloat, "intBitsToFloat"},
        {glslang::EOpUintBitsToFloat, "uintBitsToFloat"},
        {glslang::EOpPackSnorm2x16, "packSnorm2x16"},
        {glslang::EOpUnpackSnorm2x16, "unpackSnorm2x16"},
        {glslang::EOpPackUnorm2x16, "packUnorm2x16"},
        {glslang::EOpUnpackUnorm2x16, "unpackUnorm2x16"},
        {glslang::EOpPackHalf2x16, "packHalf2x16"},
        {glslang::EOpUnpackHalf2x16, "unpackHalf2x16"},
        {glslang::EOpLength, "length"},
        {glslang::EOpDistance, "distance"},
        {glslang::EOpDot, "dot"},
        {glslang::EOpCross, "cross"},
        {glslang::EOpNormalize, "normalize"},
        {glslang::EOpFaceForward, "faceforward"},
        {glslang::EOpReflect, "reflect"},
        {glslang::EOpRefract, "refract"},
        {glslang::EOpDPdx, "dFdx"},
        {glslang::EOpDPdy, "dFdy"},
        {glslang::EOpFwidth, "fwidth"},
        {glslang::EOpOuterProduct, "outerProduct"},
        {glslang::EOpDeterminant, "determinant"},
        {glslang::EOpMatrixInverse, "inverse"},
        {glslang::EOpTranspose, "transpose"},
        {glslang::EOpAny, "any"},
        {glslang::EOpAll, "all"},
        {glslang::EOpVectorLogicalNot, "not"},
};

template <std::size_t N>
const char* FindName(const BuiltinOpName (&table)[N], glslang::TOperator op) {
    for (const BuiltinOpName& entry : table) {
        if (entry.op == op) {
            return entry.name;
        }
    }
    return nullptr;
}

// The GLSL name of a built-in call node, or null when the operator is not a known built-in.
const char* BuiltinName(glslang::TOperator op, bool is_aggregate) {
    if (is_aggregate) {
        if (const char* name = FindName(kAggregateBuiltinNames, op)) {
            return name;
        }
    }
    return FindName(kBuiltinNames, op);
}

bool IsConversion(glslang::TOperator op) {
    return op >= glslang::EOpConvInt8ToBool && op <= glslang::EOpConvUvec2ToAccStruct;
}

// Operators that only move or select data; a GPU compiler folds them into the surrounding ops.
bool IsFreeOperator(glslang::TOperator op) {
    using namespace glslang;
    switch (op) {
        case EOpNull:
        case EOpSequence:
        case EOpScope:
        case EOpLinkerObjects:
        case EOpFunction:
        case EOpFunctionCall:
        case EOpParameters:
        case EOpComma:
        case EOpAssign:
        case EOpIndexDirect:
        case EOpIndexIndirect:
        case EOpIndexDirectStruct:
        case EOpVectorSwizzle:
        case EOpMatrixSwizzle:
        case EOpCopyObject:
        case EOpDeclare:
            return true;
        default:
            return IsConversion(op);
    }
}

// Classifies one operator node by the rules in StaticCost.h. User function calls are free here;
// their bodies are added by the caller of this function.
OpClass ClassifyOperator(const glslang::TIntermOperator& node, EShLanguage stage, int version) {
    const glslang::TOperator op = node.getOp();
    if (IsFreeOperator(op) || node.isConstructor()) {
        return {};
    }
    if (node.isSampling()) {
        return {OpKind::kTextureSample, TextureCallName(node, stage, version)};
    }
    const bool is_aggregate = node.getAsAggregate() != nullptr;
    // `not(bvec)` is built as the same unary node as `!b`; only the built-in takes a vector.
    if (op == glslang::EOpLogicalNot && node.getAsUnaryNode() != nullptr && node.isVector()) {
        return {OpKind::kBuiltin, "not"};
    }
    if (node.getAsBinaryNode() == nullptr) {
        if (const char* name = BuiltinName(op, is_aggregate)) {
            return {OpKind::kBuiltin, name};
        }
    }
    switch (op) {
        case glslang::EOpNegative:
        case glslang::EOpLogicalNot:
        case glslang::EOpBitwiseNot:
        case glslang::EOpPostIncrement:
        case glslang::EOpPostDecrement:
        case glslang::EOpPreIncrement:
        case glslang::EOpPreDecrement:
            return {OpKind::kArithmetic, {}};
        default:
            break;
    }
    if (node.getAsBinaryNode() != nullptr) {
        // Every binary node that is not a data move is an operator the shader wrote (+, <, &&,
        // *=, ...): glslang builds built-in calls as unary or aggregate nodes.
        return {OpKind::kArithmetic, {}};
    }
    // A built-in this table does not know yet: still one call, under a name that says so.
    return {OpKind::kBuiltin, "builtin_op_" + std::to_string(static_cast<int>(op))};
}

// A call of a built-in that glslang left as a function call (no operator) is named by its
// mangled name up to the parameter list, e.g. "foo(vf3;" becomes "foo".
std::string Demangle(const glslang::TString& mangled) {
    const std::string name(mangled.c_str());
    return name.substr(0, name.find('('));
}

// What one function body contains, not counting the bodies of the functions it calls; this is
// independent of the call site, so it is computed once per function.
struct BodySummary {
    StageCost own;  // arithmetic_ops, texture_samples, builtin_calls, branches, loops
    std::vector<std::string> callees;  // mangled names of called user functions, one per call site
    std::set<std::string> uniforms;
    std::set<std::string> varyings;
    std::set<std::string> samplers;
};

// Counts the operators, selections, loops, calls and interface symbols of one function body.
class BodyCounter : public glslang::TIntermTraverser {
public:
    BodyCounter(EShLanguage stage, int version, BodySummary* summary)
        : glslang::TIntermTraverser(/*preVisit=*/true),
          stage_(stage),
          version_(version),
          summary_(summary) {}

    void visitSymbol(glslang::TIntermSymbol* symbol) override {
        // Most symbols are locals and temporaries: the storage decides before the name is read.
        const glslang::TType& type = symbol->getType();
        std::set<std::string>* names = nullptr;
        switch (type.getQualifier().storage) {
            case glslang::EvqUniform:
                names = type.getBasicType() == glslang::EbtSampler ? &summary_->samplers
                                                                   : &summary_->uniforms;
                break;
            // In a vertex shader EvqVaryingIn is an attribute, in a fragment shader EvqVaryingOut
            // is a user output (ES 3.00), so each stage has one varying direction.
            case glslang::EvqVaryingIn:
                names = stage_ != EShLangVertex ? &summary_->varyings : nullptr;
                break;
            case glslang::EvqVaryingOut:
                names = stage_ != EShLangFragment ? &summary_->varyings : nullptr;
                break;
            default:
                break;
        }
        const char* name = symbol->getName().c_str();
        if (names != nullptr && std::strncmp(name, "gl_", 3) != 0) {
            names->insert(name);
        }
    }

    bool visitBinary(glslang::TVisit, glslang::TIntermBinary* node) override {
        Count(*node);
        return true;
    }

    bool visitUnary(glslang::TVisit, glslang::TIntermUnary* node) override {
        Count(*node);
        return true;
    }

    bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
        if (node->getOp() == glslang::EOpFunctionCall) {
            if (node->isUserDefined()) {
                summary_->callees.emplace_back(node->getName().c_str());
            } else {
                summary_->own.builtin_calls[Demangle(node->getName())] += 1;
            }
            return true;  // the arguments are evaluated at the call site
        }
        Count(*node);
        return true;
    }

    bool visitSelection(glslang::TVisit, glslang::TIntermSelection*) override {
        ++summary_->own.branches;
        return true;
    }

    bool visitLoop(glslang::TVisit, glslang::TIntermLoop*) override {
        ++summary_->own.loops;
        return true;
    }

private:
    void Count(const glslang::TIntermOperator& node) {
        OpClass op = ClassifyOperator(node, stage_, version_);
        switch (op.kind) {
            case OpKind::kFree:
                break;
            case OpKind::kArithmetic:
                ++summary_->own.arithmetic_ops;
                break;
            case OpKind::kTextureSample:
                ++summary_->own.texture_samples;
                summary_->own.builtin_calls[std::move(op.name)] += 1;
                break;
            case OpKind::kBuiltin:
                summary_->own.builtin_calls[std::move(op.name)] += 1;
                break;
        }
    }

    EShLanguage stage_;
    int version_;
    BodySummary* summary_;
};

// Cheapest and dearest op count over the paths through a piece of code.
struct PathCost {
    int shortest = 0;
    int longest = 0;
};

PathCost operator+(PathCost a, PathCost b) {
    return {AddCapped(a.shortest, b.shortest), AddCapped(a.longest, b.longest)};
}

// Works out the cost of main() and everything it calls, memoising per function.
class StageCostAnalyzer {
public:
    explicit StageCostAnalyzer(const glslang::TIntermediate& intermediate)
        : stage_(intermediate.getStage()), version_(intermediate.getVersion()) {
        glslang::TIntermAggregate* root = intermediate.getTreeRoot() != nullptr
                                                  ? intermediate.getTreeRoot()->getAsAggregate()
                                                  : nullptr;
        if (root == nullptr) {
            return;
        }
        for (TIntermNode* child : root->getSequence()) {
            glslang::TIntermAggregate* aggregate = child->getAsAggregate();
            if (aggregate != nullptr && aggregate->getOp() == glslang::EOpLinkerObjects) {
                continue;  // declarations the linker may need, not code
            }
            if (aggregate != nullptr && aggregate->getOp() == glslang::EOpFunction) {
                std::vector<TIntermNode*>& body = functions_[aggregate->getName().c_str()];
                for (TIntermNode* part : aggregate->getSequence()) {
                    glslang::TIntermAggregate* part_aggregate = part->getAsAggregate();
                    if (part_aggregate == nullptr ||
                        part_aggregate->getOp() != glslang::EOpParameters) {
                        body.push_back(part);
                    }
                }
                continue;
            }
            // Anything else at global scope (non-constant global initialisers) runs before main.
            global_code_.push_back(child);
        }
    }

    StageCost Analyze() {
        const bool has_main = functions_.count(kMainName) != 0;
        if (!has_main) {
            return {};
        }
        BodySummary entry;
        BodyCounter counter(stage_, version_, &entry);
        PathCost path;
        for (TIntermNode* node : global_code_) {
            node->traverse(&counter);
            path = path + PathOf(node);
        }
        entry.callees.emplace_back(kMainName);
        StageCost cost = Resolve(entry);
        path = path + FunctionPath(kMainName);
        cost.shortest_path_ops = path.shortest;
        cost.longest_path_ops = path.longest;
        return cost;
    }

private:
    // A function's counts including its callees, with its referenced interface symbols.
    struct FunctionTotal {
        StageCost cost;
        std::set<std::string> uniforms;
        std::set<std::string> varyings;
        std::set<std::string> samplers;
    };

    // Sums a body's own counts with those of everything it calls; the interface symbol counts
    // are filled in from the deduplicated name sets only for the entry point.
    StageCost Resolve(const BodySummary& entry) {
        FunctionTotal total = Combine(entry);
        total.cost.uniforms = static_cast<int>(total.uniforms.size());
        total.cost.varyings = static_cast<int>(total.varyings.size());
        total.cost.samplers = static_cast<int>(total.samplers.size());
        return total.cost;
    }

    FunctionTotal Combine(const BodySummary& summary) {
        FunctionTotal total{summary.own, summary.uniforms, summary.varyings, summary.samplers};
        for (const std::string& callee : summary.callees) {
            const FunctionTotal* callee_total = FunctionCounts(callee);
            if (callee_total == nullptr) {
                continue;
            }
            StageCost& cost = total.cost;
            const StageCost& add = callee_total->cost;
            cost.arithmetic_ops = AddCapped(cost.arithmetic_ops, add.arithmetic_ops);
            cost.texture_samples = AddCapped(cost.texture_samples, add.texture_samples);
            cost.branches = AddCapped(cost.branches, add.branches);
            cost.loops = AddCapped(cost.loops, add.loops);
            for (const auto& [name, count] : add.builtin_calls) {
                cost.builtin_calls[name] = AddCapped(cost.builtin_calls[name], count);
            }
            total.uniforms.insert(callee_total->uniforms.begin(), callee_total->uniforms.end());
            total.varyings.insert(callee_total->varyings.begin(), callee_total->varyings.end());
            total.samplers.insert(callee_total->samplers.begin(), callee_total->samplers.end());
        }
        return total;
    }

    // Null for a function without a body (only a prototype) and for a recursive call, both of
    // which glslang's linker rejects; counting them as empty keeps the walk finite.
    const FunctionTotal* FunctionCounts(const std::string& name) {
        if (const auto done = count_memo_.find(name); done != count_memo_.end()) {
            return &done->second;
        }
        const auto function = functions_.find(name);
        if (function == functions_.end() || !counts_in_progress_.insert(name).second) {
            return nullptr;
        }
        BodySummary summary;
        BodyCounter counter(stage_, version_, &summary);
        for (TIntermNode* node : function->second) {
            node->traverse(&counter);
        }
        FunctionTotal total = Combine(summary);
        counts_in_progress_.erase(name);
        return &(count_memo_[name] = std::move(total));
    }

    PathCost FunctionPath(const std::string& name) {
        if (const auto done = path_memo_.find(name); done != path_memo_.end()) {
            return done->second;
        }
        const auto function = functions_.find(name);
        if (function == functions_.end() || !paths_in_progress_.insert(name).second) {
            return {};
        }
        PathCost path;
        for (TIntermNode* node : function->second) {
            path = path + PathOf(node);
        }
        paths_in_progress_.erase(name);
        path_memo_[name] = path;
        return path;
    }

    // ClassifyOperator's kind is kFree exactly for these; the name it builds is not needed here.
    static int OwnOps(const glslang::TIntermOperator& node) {
        return IsFreeOperator(node.getOp()) || node.isConstructor() ? 0 : 1;
    }

    // A selection takes the cheaper or dearer arm; everything else is the sum of its parts.
    PathCost PathOf(TIntermNode* node) {
        if (node == nullptr) {
            return {};
        }
        if (glslang::TIntermSelection* selection = node->getAsSelectionNode()) {
            const PathCost when_true = PathOf(selection->getTrueBlock());
            const PathCost when_false = PathOf(selection->getFalseBlock());
            return PathOf(selection->getCondition()) +
                   PathCost{std::min(when_true.shortest, when_false.shortest),
                            std::max(when_true.longest, when_false.longest)};
        }
        if (glslang::TIntermLoop* loop = node->getAsLoopNode()) {
            return PathOf(loop->getTest()) + PathOf(loop->getBody()) + PathOf(loop->getTerminal());
        }
        if (glslang::TIntermBranch* branch = node->getAsBranchNode()) {
            return PathOf(branch->getExpression());
        }
        if (glslang::TIntermSwitch* switch_node = node->getAsSwitchNode()) {
            // GLSL ES 3.00 only; counted as one path through every case, like TotalOps().
            return PathOf(switch_node->getCondition()) + PathOf(switch_node->getBody());
        }
        if (glslang::TIntermBinary* binary = node->getAsBinaryNode()) {
            const int own = OwnOps(*binary);
            return PathOf(binary->getLeft()) + PathOf(binary->getRight()) + PathCost{own, own};
        }
        if (glslang::TIntermUnary* unary = node->getAsUnaryNode()) {
            const int own = OwnOps(*unary);
            return PathOf(unary->getOperand()) + PathCost{own, own};
        }
        if (glslang::TIntermAggregate* aggregate = node->getAsAggregate()) {
            PathCost path;
            for (TIntermNode* child : aggregate->getSequence()) {
                path = path + PathOf(child);
            }
            if (aggregate->getOp() == glslang::EOpFunctionCall) {
                if (aggregate->isUserDefined()) {
                    return path + FunctionPath(aggregate->getName().c_str());
                }
                return path + PathCost{1, 1};  // a built-in left as a call
            }
            const int own = OwnOps(*aggregate);
            return path + PathCost{own, own};
        }
        return {};  // symbols and constants
    }

    EShLanguage stage_;
    int version_;
    std::unordered_map<std::string, std::vector<TIntermNode*>> functions_;  // mangled name → body
    std::vector<TIntermNode*> global_code_;
    std::unordered_map<std::string, FunctionTotal> count_memo_;
    std::unordered_map<std::string, PathCost> path_memo_;
    std::unordered_set<std::string> counts_in_progress_;
    std::unordered_set<std::string> paths_in_progress_;
};

// glslang's pool-allocated containers (the traverser's path stack) allocate from the thread's
// current pool, which is whatever TShader or TProgram last set and may already be destroyed; a
// pool of our own for the analysis avoids writing into someone else's, and the old one is put
// back afterwards.
class ScopedPoolAllocator {
public:
    ScopedPoolAllocator() : previous_(&glslang::GetThreadPoolAllocator()) {
        glslang::SetThreadPoolAllocator(&pool_);
    }
    ~ScopedPoolAllocator() { glslang::SetThreadPoolAllocator(previous_); }
    ScopedPoolAllocator(const ScopedPoolAllocator&) = delete;
    ScopedPoolAllocator& operator=(const ScopedPoolAllocator&) = delete;

private:
    glslang::TPoolAllocator pool_;
    glslang::TPoolAllocator* previous_;
};

}  // namespace

StageCost AnalyzeStageCost(const glslang::TIntermediate& intermediate) {
    ScopedPoolAllocator pool;
    return StageCostAnalyzer(intermediate).Analyze();
}

std::optional<StageCost> AnalyzeSourceCost(std::string_view glsl_es_source, bool is_fragment,
                                           std::string* error_log) {
    // glslang needs one process-wide initialisation; it is never finalised because other parts of
    // the compiler may still be using glslang when this caller is done.
    static const bool initialized = glslang::InitializeProcess();
    if (!initialized) {
        if (error_log != nullptr) {
            *error_log = "glslang::InitializeProcess failed";
        }
        return std::nullopt;
    }
    glslang::TShader shader(is_fragment ? EShLangFragment : EShLangVertex);
    const char* text = glsl_es_source.data();
    const int length = static_cast<int>(glsl_es_source.size());
    shader.setStringsWithLengths(&text, &length, 1);
    constexpr int kDefaultEsVersion = 100;  // GLSL ES 1.00, when the source has no #version
    if (!shader.parse(GetDefaultResources(), kDefaultEsVersion, EEsProfile,
                      /*forceDefaultVersionAndProfile=*/false, /*forwardCompatible=*/false,
                      EShMsgDefault)) {
        if (error_log != nullptr) {
            *error_log = shader.getInfoLog();
        }
        return std::nullopt;
    }
    if (error_log != nullptr) {
        error_log->clear();
    }
    return AnalyzeStageCost(*shader.getIntermediate());
}

int StageCost::TotalOps() const {
    int total = arithmetic_ops;
    for (const auto& [name, count] : builtin_calls) {
        total = AddCapped(total, count);
    }
    return total;
}

nlohmann::json ToJson(const StageCost& cost) {
    return nlohmann::json{
            {"arithmetic_ops", cost.arithmetic_ops},
            {"texture_samples", cost.texture_samples},
            {"builtin_calls", cost.builtin_calls},
            {"branches", cost.branches},
            {"loops", cost.loops},
            {"uniforms", cost.uniforms},
            {"varyings", cost.varyings},
            {"samplers", cost.samplers},
            {"shortest_path_ops", cost.shortest_path_ops},
            {"longest_path_ops", cost.longest_path_ops},
            {"total_ops", cost.TotalOps()},
    };
}

}  // namespace tidepool
