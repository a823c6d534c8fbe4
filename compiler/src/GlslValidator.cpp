// glslang is wrapped here: it is initialised once per process, its text info log is turned into
// Diagnostics at the user's own lines (defines travel through TShader::setPreamble, so the user's
// file is string 0 and keeps its numbering), and nothing of it leaks through the public header.
#include "tidepool/GlslValidator.h"

#include "tidepool/TextFile.h"
#include "tidepool/base/CacheBundle.h"
#include "tidepool/base/Sha256.h"
#include "tidepool/base/WorkerProcessPool.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "CompilerSourceDigest.h"
#include "DefineRelevance.h"
#include "GlslEsRules.h"
#include "GlslangSession.h"
#include "StaticCostAnalyzer.h"
#include <fmt/format.h>

namespace tidepool {

using base::ProgressNote;
using base::RunInWorkerProcesses;
using base::WorkerFailure;
using base::WorkerItemResult;
using base::WorkerLimits;

int ValidationReport::InvalidCount() const {
    return static_cast<int>(std::count_if(verdicts.begin(), verdicts.end(),
                                          [](const VariantVerdict& v) { return !v.valid; }));
}

const char* StepStatusName(StepStatus status) {
    switch (status) {
        case StepStatus::kValid:
            return "valid";
        case StepStatus::kInvalid:
            return "invalid";
        case StepStatus::kNotRun:
            break;
    }
    return "not run";
}

bool StageFromExtension(const std::string& path, Stage* stage) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".vert" || ext == ".vsh" || ext == ".vs") {
        *stage = Stage::kVertex;
        return true;
    }
    if (ext == ".frag" || ext == ".fsh" || ext == ".fs") {
        *stage = Stage::kFragment;
        return true;
    }
    return false;
}

namespace {

// glslang runs in worker processes (WorkerProcessPool.h): a shader that crashes it, loops it or
// makes it allocate without bound fails its own stage with an "internal compiler error" and the
// run goes on. The limits are per worker and item. 1 GiB is five times what validating the whole
// default matrix takes (about 190 MB); 20 s is a hundred times the slowest shipped stage under
// the sanitizers on a loaded two-core machine. Items take a millisecond or less, so each worker
// holds the next one while it runs one, each parse allocates and frees a few hundred KiB, so
// a worker keeps freed memory mapped, and a worker's items are next to each other, so that it
// parses a stage that several links share once. Each worker runs glslang on a 128 MiB stack:
// glslang's preprocessor recurses once for each parenthesis and unary operator of an `#if`
// expression, a shader's expansion is capped at kMaxExpandedTokens (131,072) tokens, and on the
// usual 8 MiB an `#if` of 60,000 nested parentheses crashed it (about 24 MiB at the cap, at
// glslang's 180 bytes or so a level; more under the sanitizers).
constexpr WorkerLimits kGlslangLimits{std::uint64_t{1} << 30, 20.0, 1, true, true,
                                      std::size_t{128} << 20};

// The limits in force. TIDEPOOL_TEST_GLSLANG_SECONDS (a number of seconds) lowers the time
// limit so that tests can see a hang of glslang handled end to end in a second instead of 20;
// it can only lower it, so no environment switches the guard off.
const WorkerLimits& GlslangLimits() {
    static const WorkerLimits limits = [] {
        WorkerLimits chosen = kGlslangLimits;
        if (const char* text = std::getenv("TIDEPOOL_TEST_GLSLANG_SECONDS"); text != nullptr) {
            char* end = nullptr;
            const double seconds = std::strtod(text, &end);
            if (end != text && *end == '\0' && seconds > 0 && seconds < chosen.seconds_per_item) {
                chosen.seconds_per_item = seconds;
            }
        }
        return chosen;
    }();
    return limits;
}

// What a failed worker item means for the stage or link it was working on.
std::string InternalCompilerError(const WorkerItemResult& result, std::string_view doing) {
    std::string what;
    switch (result.failure) {
        case WorkerFailure::kOutOfMemory:
            what = fmt::format("glslang ran out of memory (limit {} MiB)",
                               GlslangLimits().memory_bytes >> 20);
            break;
        case WorkerFailure::kTimedOut:
            what = fmt::format("glslang took longer than {} s", GlslangLimits().seconds_per_item);
            break;
        default:
            what = fmt::format("glslang crashed ({})", result.detail);
            break;
    }
    return fmt::format(
            "internal compiler error: {} while {}; the shader may be valid or not, "
            "and the run went on without it",
            what, doing);
}

// Worker notes of a stage-and-link item: "P<i>" before parsing stage i, "S<i>:" and its outcome's
// record (WriteOutcome) after, "L" before linking. The last note names the step a failure
// happened in.
struct StageOutcome {
    bool valid = false;
    std::vector<Diagnostic> diagnostics;
    StageCost cost;
    bool has_cost = false;  // the cost was worked out (ValidationOptions::static_costs)
};

// The bytes a worker reports a stage or a link in, and the cache keeps them in: fixed-width
// little-endian integers and length-prefixed strings, not CBOR (nlohmann's CBOR reader made the
// decoding of a warm run's stages a fifth of the run). Diagnostics may quote bytes that are not
// UTF-8, which this carries unchanged. The reader checks every length against what is left, so
// bytes that are not a record read as none.
class EntryWriter {
public:
    void Int(std::int64_t value) {
        const auto bits = static_cast<std::uint64_t>(value);
        for (int shift = 0; shift < 64; shift += 8) {
            bytes_.push_back(static_cast<char>((bits >> shift) & 0xffU));
        }
    }
    void Text(std::string_view text) {
        Int(static_cast<std::int64_t>(text.size()));
        bytes_.append(text);
    }
    std::string& Bytes() { return bytes_; }

private:
    std::string bytes_;
};

class EntryReader {
public:
    explicit EntryReader(std::string_view bytes) : rest_(bytes) {}
    bool Tag(std::string_view tag) {
        if (rest_.substr(0, tag.size()) != tag) {
            return Fail();
        }
        rest_.remove_prefix(tag.size());
        return true;
    }
    std::int64_t Int() {
        if (rest_.size() < 8) {
            Fail();
            return 0;
        }
        std::uint64_t bits = 0;
        for (int i = 7; i >= 0; --i) {
            bits = (bits << 8) | static_cast<unsigned char>(rest_[static_cast<std::size_t>(i)]);
        }
        rest_.remove_prefix(8);
        return static_cast<std::int64_t>(bits);
    }
    // An int that must fit `int` (line numbers, counts): anything else is not an entry.
    int SmallInt() {
        const std::int64_t value = Int();
        if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) {
            Fail();
            return 0;
        }
        return static_cast<int>(value);
    }
    std::string Text() {
        const std::int64_t size = Int();
        if (size < 0 || static_cast<std::uint64_t>(size) > rest_.size()) {
            Fail();
            return {};
        }
        std::string text(rest_.substr(0, static_cast<std::size_t>(size)));
        rest_.remove_prefix(static_cast<std::size_t>(size));
        return text;
    }
    // A count of items that each take at least `min_bytes`, so a bad count cannot reserve much.
    std::size_t Count(std::size_t min_bytes) {
        const std::int64_t count = Int();
        if (count < 0 || static_cast<std::uint64_t>(count) > rest_.size() / min_bytes) {
            Fail();
            return 0;
        }
        return static_cast<std::size_t>(count);
    }
    bool Ok() const { return ok_; }
    bool AtEnd() const { return ok_ && rest_.empty(); }

private:
    bool Fail() {
        ok_ = false;
        rest_ = {};
        return false;
    }
    std::string_view rest_;
    bool ok_ = true;
};

void WriteDiagnostics(EntryWriter& out, const std::vector<Diagnostic>& diagnostics) {
    out.Int(static_cast<std::int64_t>(diagnostics.size()));
    for (const Diagnostic& d : diagnostics) {
        out.Int(static_cast<int>(d.severity));
        out.Text(d.file);
        out.Int(d.line);
        out.Int(d.column);
        out.Text(d.message);
    }
}

bool ReadDiagnostics(EntryReader& in, std::vector<Diagnostic>* diagnostics) {
    const std::size_t count = in.Count(40);  // five fields of at least 8 bytes
    for (std::size_t i = 0; i < count && in.Ok(); ++i) {
        Diagnostic d;
        const int severity = in.SmallInt();
        if (severity < 0 || severity > static_cast<int>(Severity::kNote)) {
            return false;
        }
        d.severity = static_cast<Severity>(severity);
        d.file = in.Text();
        d.line = in.SmallInt();
        d.column = in.SmallInt();
        d.message = in.Text();
        diagnostics->push_back(std::move(d));
    }
    return in.Ok();
}

// `cost` null: the cost was not worked out.
void WriteOutcome(EntryWriter& out, bool valid, const std::vector<Diagnostic>& diagnostics,
                  const StageCost* cost) {
    out.Int(valid ? 1 : 0);
    WriteDiagnostics(out, diagnostics);
    out.Int(cost != nullptr ? 1 : 0);
    if (cost == nullptr) {
        return;
    }
    for (int value :
         {cost->arithmetic_ops, cost->texture_samples, cost->branches, cost->loops, cost->uniforms,
          cost->varyings, cost->samplers, cost->shortest_path_ops, cost->longest_path_ops}) {
        out.Int(value);
    }
    out.Int(static_cast<std::int64_t>(cost->builtin_calls.size()));
    for (const auto& [name, count] : cost->builtin_calls) {
        out.Text(name);
        out.Int(count);
    }
}

// The outcome WriteOutcome wrote, up to the end of the bytes; none when they are not one.
std::optional<StageOutcome> ReadOutcome(EntryReader& in) {
    StageOutcome outcome;
    const std::int64_t valid = in.Int();
    outcome.valid = valid == 1;
    if (!ReadDiagnostics(in, &outcome.diagnostics)) {
        return std::nullopt;
    }
    const std::int64_t has_cost = in.Int();
    outcome.has_cost = has_cost == 1;
    if (has_cost == 0 && in.AtEnd() && (valid == 0 || valid == 1)) {
        return outcome;
    }
    StageCost& cost = outcome.cost;
    for (int* field :
         {&cost.arithmetic_ops, &cost.texture_samples, &cost.branches, &cost.loops, &cost.uniforms,
          &cost.varyings, &cost.samplers, &cost.shortest_path_ops, &cost.longest_path_ops}) {
        *field = in.SmallInt();
    }
    const std::size_t calls = in.Count(16);
    for (std::size_t i = 0; i < calls && in.Ok(); ++i) {
        std::string name = in.Text();
        cost.builtin_calls[std::move(name)] = in.SmallInt();
    }
    if (!in.AtEnd() || (valid != 0 && valid != 1) || has_cost != 1) {
        return std::nullopt;
    }
    return outcome;
}

// A link's record starts with this, so that a cache entry of another kind is not taken for one.
constexpr std::string_view kLinkTag = "tidepool link 1\n";

// With `costs`, the stage's StaticCost is worked out. An invalid stage's is empty, and known
// without it.
std::string EncodeStage(std::size_t index, const StageParse& parse, bool costs) {
    StageCost cost;
    if (costs && parse.ok && parse.intermediate != nullptr) {
        cost = AnalyzeStageCost(*parse.intermediate);
    }
    EntryWriter out;
    out.Bytes() = fmt::format("S{}:", index);
    WriteOutcome(out, parse.ok, parse.diagnostics, costs || !parse.ok ? &cost : nullptr);
    return std::move(out.Bytes());
}

// The stage outcomes an item reported, by index into `programs`; none for a report that does
// not decode.
std::map<std::size_t, std::optional<StageOutcome>> DecodeStages(
        const std::vector<std::string>& notes, const std::vector<StageProgram>& programs) {
    std::map<std::size_t, std::optional<StageOutcome>> stages;
    for (const std::string& note : notes) {
        const std::size_t colon = note.find(':');
        if (note.empty() || note[0] != 'S' || colon == std::string::npos) {
            continue;
        }
        std::size_t index = 0;
        const char* digits = note.data() + 1;
        if (std::from_chars(digits, note.data() + colon, index).ptr != note.data() + colon ||
            index >= programs.size()) {
            continue;  // names no stage program
        }
        EntryReader in(std::string_view(note).substr(colon + 1));
        stages[index] = ReadOutcome(in);
    }
    return stages;
}

// Puts a worker's report of a stage into `program`: its outcome, or an internal compiler error
// when the report does not decode (then `*internal_errors` is set). True when the outcome is
// glslang's own verdict, the one the cache may keep.
bool TakeStageReport(std::optional<StageOutcome> outcome, StageProgram& program,
                     bool* internal_errors) {
    const bool own_verdict = outcome.has_value();
    if (!own_verdict) {
        outcome = StageOutcome{
                false,
                {MakeError(program.file, 0, 0,
                           "internal compiler error: the worker's report of this stage could not "
                           "be read; run again, and report a bug if it persists")},
                {},
                false};
        *internal_errors = true;
    }
    program.valid = outcome->valid;
    program.diagnostics = std::move(outcome->diagnostics);
    program.cost = std::move(outcome->cost);
    return own_verdict;
}

// One stage of a link item, as the worker sees it.
struct ItemStage {
    std::size_t index = 0;  // the stage program's index, for notes
    GlslangStageInput input;
};

// Parses a worker keeps for its later links, by stage program index. Most links of a matrix share
// their vertex stage with others (163 links of 18 vertex and 155 fragment stages in the default
// matrix), and a parse is most of a link item's cost.
struct KeptParses {
    // Links not yet run that use each stage program, as this worker knows them.
    std::vector<int> uses;
    std::map<std::size_t, StageParse> parses;
};

// At most this many parses are kept per worker (a parse of shaders/water.fsh holds 0.1 to
// 0.35 MB; a worker may use 1 GiB).
constexpr std::size_t kMaxKeptParses = 64;

// Worker side of a link item: parses each stage (reporting it through a note, with its cost when
// `costs` asks, unless this worker already did: its cost analysis is not free) or takes the
// parse `kept` holds, and when all parsed, links them; returns the link's outcome, or "" when no
// link ran. With `kept`, a parse a later link may use and that the link left reusable is kept
// for it.
std::string ParseAndLink(const std::vector<ItemStage>& stages, const ProgressNote& note, bool costs,
                         std::vector<bool>* reported, KeptParses* kept = nullptr) {
    std::vector<StageParse> parses;
    bool all_ok = true;
    for (const ItemStage& stage : stages) {
        if (kept != nullptr) {
            --kept->uses[stage.index];
            if (auto it = kept->parses.find(stage.index); it != kept->parses.end()) {
                parses.push_back(std::move(it->second));
                kept->parses.erase(it);
                continue;  // kept only when it parsed, so reported and valid
            }
        }
        note(fmt::format("P{}", stage.index));
        parses.push_back(ParseStage(stage.input));
        if (!(*reported)[stage.index]) {
            note(EncodeStage(stage.index, parses.back(), costs));
            (*reported)[stage.index] = true;
        }
        all_ok = all_ok && parses.back().ok;
    }
    if (!all_ok) {
        return {};
    }
    note("L");
    std::vector<const GlslangStageInput*> inputs;
    std::vector<StageParse*> parsed;
    for (std::size_t i = 0; i < stages.size(); ++i) {
        inputs.push_back(&stages[i].input);
        parsed.push_back(&parses[i]);
    }
    const LinkResult link = LinkParsed(inputs, parsed);
    if (kept != nullptr) {
        for (std::size_t i = 0; i < stages.size(); ++i) {
            if (kept->uses[stages[i].index] > 0 && kept->parses.size() < kMaxKeptParses &&
                ReusableForLink(parses[i])) {
                kept->parses.emplace(stages[i].index, std::move(parses[i]));
            }
        }
    }
    EntryWriter out;
    out.Bytes().append(kLinkTag);
    out.Int(link.ok ? 1 : 0);
    WriteDiagnostics(out, link.diagnostics);
    return std::move(out.Bytes());
}

// A link's outcome from ParseAndLink's encoding (also the link entries of the cache); none when
// the bytes are not one.
std::optional<LinkResult> DecodeLink(std::string_view payload) {
    EntryReader in(payload);
    if (!in.Tag(kLinkTag)) {
        return std::nullopt;
    }
    LinkResult link;
    const std::int64_t ok = in.Int();
    link.ok = ok == 1;
    if (!ReadDiagnostics(in, &link.diagnostics) || !in.AtEnd() || (ok != 0 && ok != 1)) {
        return std::nullopt;
    }
    return link;
}

// Parent side of a link item: the link's outcome, or the internal compiler error of whichever
// step failed (a stage, reported through `on_stage_error`, or the link itself).
// `*glslangs_verdict` says whether the outcome is glslang's own verdict on a link that ran, the
// one the cache may keep (the item's payload).
LinkResult LinkOutcome(const WorkerItemResult& result, std::string_view link_file,
                       const std::function<void(std::size_t, const std::string&)>& on_stage_error,
                       bool* glslangs_verdict) {
    LinkResult link;
    *glslangs_verdict = false;
    if (result.failure == WorkerFailure::kNone) {
        if (!result.payload.empty()) {
            if (std::optional<LinkResult> decoded = DecodeLink(result.payload)) {
                link = std::move(*decoded);
                *glslangs_verdict = true;
            } else {
                link.diagnostics.push_back(MakeError(
                        std::string(link_file), 0, 0,
                        "internal compiler error: the worker's report of this link could not be "
                        "read; run again, and report a bug if it persists"));
            }
        }
        return link;
    }
    if (result.failure == WorkerFailure::kSkipped) {
        return link;
    }
    const std::string last = result.notes.empty() ? std::string("L") : result.notes.back();
    if (last[0] == 'P') {
        on_stage_error(std::stoul(last.substr(1)),
                       InternalCompilerError(result, "parsing this stage"));
    } else {
        link.diagnostics.push_back(MakeError(std::string(link_file), 0, 0,
                                             InternalCompilerError(result, "linking the program")));
    }
    return link;
}

std::string Fnv1a64Hex(std::string_view text) {
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    for (char c : text) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 0x100000001b3ULL;
    }
    return fmt::format("{:016x}", hash);
}

struct FileText {
    bool ok = false;
    std::string text;
    std::string error;                    // why it could not be read
    std::vector<Diagnostic> text_errors;  // CheckSourceText's findings: glslang never sees it
};

FileText ReadFile(const std::filesystem::path& path, const std::string& name,
                  const std::vector<std::string>& defines = {}) {
    TextFileRead read = ReadShaderFile(path);
    FileText file{read.ok, std::move(read.text), std::move(read.error), {}};
    if (file.ok) {
        file.text_errors = CheckSourceText(file.text, DefinePreamble(defines), name);
    }
    return file;
}

// One (file, stage, target, defines) to compile; the unit of preprocessing and hashing.
struct StageJob {
    std::string file;
    const FileText* source = nullptr;
    Stage stage = Stage::kVertex;
    GlslTarget target = GlslTarget::kEs100;
    std::vector<std::string> defines;
    const DeviceLimits* limits = nullptr;  // the device's, when given
    const Variant* variant = nullptr;      // the variant this slot belongs to
    std::string variant_id;
    std::string key;                // dedupe key: file + stage + target + content hash
    std::string hash;               // content hash of the preprocessed text
    std::string digest;             // SHA-256 of the same text, for the cache's link keys
    std::vector<LineSpan> skipped;  // code lines glslang skips here, when the walk followed it
};

void HashStage(StageJob& job) {
    const GlslangStageInput input{job.file,   job.source->text, job.stage,
                                  job.target, job.defines,      job.limits};
    const PreprocessResult pre = PreprocessStage(input);
    // A stage that does not even preprocess gets a hash of its raw input, so it stays distinct
    // per define set and the parse reports the error at its line.
    const std::string material =
            pre.ok ? pre.text : job.source->text + "\n//" + DefinePreamble(job.defines);
    // The device's limits decide verdicts as much as the text does.
    const std::string text =
            fmt::format("{}|{}|{}|{}", StageName(job.stage), TargetName(job.target),
                        job.limits != nullptr ? job.limits->Text() : "", material);
    job.hash = Fnv1a64Hex(text);
    job.digest = base::Sha256Hex(text);
    job.key = job.file + "|" + job.hash;
}

// The part of a stage's identity that can change glslang's preprocessed output: `target` is a
// target's name or, for a plain file, PlainTargetLabel's. A define is kept, with its value, when
// its name (before any `=VALUE`, which plain files' -D may add) is mentioned, or when glslang may
// refuse it in the preamble (IsPlainDefine).
std::string StageGroupKey(const std::string& file, Stage stage, const std::string& target,
                          const DeviceLimits* limits, const std::vector<std::string>& defines,
                          const std::set<std::string>& mentioned) {
    std::string key = fmt::format("{}|{}|{}|{}|", file, StageName(stage), target,
                                  limits != nullptr ? limits->Text() : "");
    for (const std::string& define : defines) {
        // One glslang may refuse in the preamble counts wherever the file's text is; every one
        // counts in a text that pastes tokens.
        if (mentioned.count(define.substr(0, define.find('='))) != 0 || !IsPlainDefine(define) ||
            mentioned.count(kPastesTokens) != 0) {
            key += define + ",";
        }
    }
    return key;
}

std::string PreprocessGroupKey(const StageJob& job, const std::set<std::string>& mentioned) {
    return StageGroupKey(job.file, job.stage, TargetName(job.target), job.limits, job.defines,
                         mentioned);
}

// The target part of a plain file's stage key. A plain file is compiled as the GLSL ES version of
// its own `#version` line (a configuration's stage as its target's), so its keys are kept apart
// from a configuration's: "file", or "file:webgl1" with --target.
std::string PlainTargetLabel(const std::optional<GlslTarget>& target) {
    return target ? "file:" + TargetName(*target) : "file";
}

// The start of every cache key: the validation code and what glslang decides with, as one
// digest (the resource limits alone are kilobytes, too much to hash again for every key).
const std::string& CacheKeyPrefix() {
    static const std::string prefix =
            base::Sha256Hex(fmt::format("tidepool validation cache 1\n{}\n{}\n",
                                        kCompilerSourceDigest, GlslangIdentity())) +
            "\n";
    return prefix;
}

// The cache key of a preprocessing group: its file's name and text (as a digest) and what
// PreprocessGroupKey keeps, which decide glslang's input exactly (see MentionedIdentifiers).
std::string StageCacheKey(const std::string& group_key, const std::string& file_digest) {
    return base::Sha256()
            .Update(CacheKeyPrefix())
            .Update("stage\n")
            .Update(group_key)
            .Update("\n")
            .Update(file_digest)
            .FinishHex();
}

// The cache key of a link: both stages' files and preprocessed texts (as digests).
std::string LinkCacheKey(const StageJob& vertex, const StageJob& fragment) {
    return base::Sha256()
            .Update(CacheKeyPrefix())
            .Update(fmt::format("link\n{}\n{}\n{}\n{}\n", vertex.file, vertex.digest, fragment.file,
                                fragment.digest))
            .FinishHex();
}

// The cache key of a plain-file link (or of a lone stage's): the stage keys, which decide each
// stage's input to glslang exactly, so no preprocessing is needed to find it.
std::string PlainLinkCacheKey(const std::vector<std::string>& stage_keys) {
    base::Sha256 key;
    key.Update(CacheKeyPrefix()).Update("plain link\n");
    for (const std::string& stage_key : stage_keys) {
        key.Update(stage_key).Update("\n");
    }
    return key.FinishHex();
}

// The name of a configuration's latest bundle of results: its file and the programs validated,
// so that a run after an edit finds the results the edit did not change.
std::string LineageKey(const VariantConfig& config, const std::vector<Variant>& variants) {
    std::set<std::string> programs;
    for (const Variant& variant : variants) {
        programs.insert(variant.program);
    }
    std::error_code ec;
    const std::filesystem::path file = std::filesystem::absolute(config.path, ec);
    return base::Sha256()
            .Update(CacheKeyPrefix())
            .Update(fmt::format("lineage\n{}\n{}\n", file.string(), fmt::join(programs, ",")))
            .FinishHex();
}

// A stage program's outcome as the cache stores it, with the two hashes of its text.
struct CachedStage {
    std::string hash;
    std::string digest;
    StageOutcome outcome;
};

// A cached stage's bytes: a tag, the two hashes, then the outcome as a worker reports it. The
// entry is already checksummed by the cache; bytes that are not an entry are a miss.
constexpr std::string_view kCachedStageTag = "tidepool stage 1\n";

std::string EncodeCachedStage(const StageProgram& program, const std::string& digest,
                              bool has_cost) {
    EntryWriter out;
    out.Bytes().append(kCachedStageTag);
    out.Text(program.hash);
    out.Text(digest);
    WriteOutcome(out, program.valid, program.diagnostics, has_cost ? &program.cost : nullptr);
    return std::move(out.Bytes());
}

// The entry's outcome, or none when it does not decode (it is then recomputed and replaced).
std::optional<CachedStage> DecodeCachedStage(const std::string& payload) {
    EntryReader in(payload);
    if (!in.Tag(kCachedStageTag)) {
        return std::nullopt;
    }
    CachedStage stage;
    stage.hash = in.Text();
    stage.digest = in.Text();
    std::optional<StageOutcome> outcome = ReadOutcome(in);
    if (!outcome) {
        return std::nullopt;
    }
    stage.outcome = std::move(*outcome);
    return stage;
}

std::vector<Diagnostic> Tagged(std::vector<Diagnostic> diagnostics, const std::string& id) {
    for (Diagnostic& d : diagnostics) {
        d.variant = id;
    }
    return diagnostics;
}

// A step that ran, with its messages tagged with the variant.
StepVerdict RanStep(bool valid, const std::vector<Diagnostic>& diagnostics, const std::string& id) {
    return StepVerdict{valid ? StepStatus::kValid : StepStatus::kInvalid, Tagged(diagnostics, id)};
}

// Fills `verdict.diagnostics` from its steps, vertex, fragment, then link.
void CollectStepDiagnostics(VariantVerdict& verdict) {
    for ([[maybe_unused]] const auto& [name, step] : verdict.NamedSteps()) {
        verdict.diagnostics.insert(verdict.diagnostics.end(), step->diagnostics.begin(),
                                   step->diagnostics.end());
    }
}

}  // namespace

const std::string& ValidationCacheIdentity() {
    return CacheKeyPrefix();
}

GlslangWarmUp::GlslangWarmUp(std::vector<GlslTarget> targets)
    : targets_(std::move(targets)), thread_([this] {
          placed_.wait(false);  // so that AllowAll comes after StartThreadAway
          placement_.AllowAll();
          try {
              WarmUpGlslang(targets_);
          } catch (...) {
              // Nothing lost but time: each worker then builds the tables it needs itself.
          }
      }) {
    placement_.StartThreadAway(thread_.native_handle(), 0);
    placed_ = true;
    placed_.notify_one();
}

const std::vector<GlslTarget>& GlslangWarmUp::Finish() {
    if (thread_.joinable()) {
        thread_.join();
    }
    return targets_;
}

ValidationReport ValidateVariants(const VariantConfig& config, const std::vector<Variant>& variants,
                                  const ValidationOptions& options) {
    ValidationReport report;
    base::ContentCache* const cache = options.cache;
    const std::uint64_t stored_before = cache != nullptr ? cache->Stats().stored : 0;
    // The run's results are read and written as one cache entry (CacheBundle.h).
    std::optional<base::CacheBundle> bundle;
    // Before the first workers fork, so none builds the tables again; not at all when the cache
    // answers everything. When the cache knows no earlier run of this configuration (or there is
    // no cache), glslang will be needed: unless the caller started it earlier, its tables are
    // built on a second thread while this one reads the files and groups the stages (a tenth of
    // a cold validation's time before the workers start), and warm_up waits for it, so the fork
    // sees one thread.
    const std::string lineage = cache != nullptr ? LineageKey(config, variants) : std::string();
    std::optional<GlslangWarmUp> own_warm_up;
    GlslangWarmUp* warming = options.warm_up;
    if (warming == nullptr && (cache == nullptr || !cache->Load(lineage).has_value())) {
        warming = &own_warm_up.emplace(options.targets);
    }
    std::vector<GlslTarget> warmed;  // targets whose tables this process has
    auto finish_warming = [&] {      // before every fork: a child has the forking thread only
        if (warming != nullptr) {
            warmed = warming->Finish();
            warming = nullptr;
        }
    };
    auto warm_up = [&] {
        finish_warming();
        std::vector<GlslTarget> missing;
        for (GlslTarget target : options.targets) {
            if (std::find(warmed.begin(), warmed.end(), target) == warmed.end()) {
                missing.push_back(target);
            }
        }
        if (!missing.empty()) {
            WarmUpGlslang(missing);
            warmed.insert(warmed.end(), missing.begin(), missing.end());
        }
    };

    // Read every shader file once.
    std::map<std::string, FileText> files;
    for (const ProgramConfig& program : config.programs) {
        for (const std::string& path : {program.vertex_path, program.fragment_path}) {
            if (files.count(path) == 0) {
                files[path] = ReadFile(config.Resolve(path), path);
                if (!files[path].ok) {
                    report.diagnostics.push_back(MakeError(
                            path, 0, 0,
                            fmt::format("cannot read shader file: {}; check the path in {}",
                                        files[path].error, config.path)));
                }
            }
        }
    }

    // 1. Preprocess and hash every stage slot.
    std::vector<StageJob> jobs;
    for (GlslTarget target : options.targets) {
        for (const Variant& variant : variants) {
            const ProgramConfig* program = config.FindProgram(variant.program);
            if (program == nullptr) {
                continue;  // a variant of another configuration: nothing to compile it from
            }
            for (Stage stage : {Stage::kVertex, Stage::kFragment}) {
                StageJob job;
                job.file = stage == Stage::kVertex ? program->vertex_path : program->fragment_path;
                job.source = &files[job.file];
                job.stage = stage;
                job.target = target;
                job.defines = variant.defines;
                job.limits = options.limits;
                job.variant = &variant;
                job.variant_id = variant.Id();
                jobs.push_back(std::move(job));
            }
        }
    }
    report.stage_slots = static_cast<int>(jobs.size());
    // A file glslang must not see (unreadable, or refused by CheckSourceText) is one program.
    auto blocked = [](const StageJob& job) {
        return !job.source->ok || !job.source->text_errors.empty();
    };
    // Slots that give glslang the same preprocessed text form one group, parsed once. Where the
    // walk of a file's conditionals follows it (DefineRelevance), the defines it finds relevant
    // decide the group exactly, and the group is a stage program without preprocessing anything.
    // Elsewhere, slots whose defines differ only in names the file never mentions form a group,
    // preprocessed once (glslang's preprocessor costs nearly a parse) to hash its text.
    std::map<std::string, std::set<std::string>> mentioned;  // made for the walk's misses only
    std::map<std::string, DefineRelevance> relevance;
    for (const auto& [path, text] : files) {
        relevance.emplace(path, DefineRelevance(text.text));
    }
    std::map<std::string, std::vector<std::size_t>> groups;
    std::set<std::string> exact_keys;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        StageJob& job = jobs[i];
        // A 3.00 target gives a 1.00 file a preamble of macros (texture2D, ...) the walk does not
        // know of; such slots are grouped by their text.
        std::optional<std::string> relevant;
        if (!blocked(job) && TargetVersion(job.target) == 100) {
            relevant = relevance.at(job.file).Relevant(job.defines, &job.skipped);
        }
        if (relevant) {
            std::string key =
                    StageGroupKey(job.file, job.stage, TargetName(job.target), job.limits, {}, {}) +
                    "walk|" + *relevant;
            exact_keys.insert(key);
            groups[std::move(key)].push_back(i);
        } else {
            if (mentioned.count(job.file) == 0) {
                mentioned[job.file] = MentionedIdentifiers(job.source->text);
            }
            groups[PreprocessGroupKey(job, mentioned[job.file])].push_back(i);
        }
    }
    std::vector<const std::vector<std::size_t>*> group_list;
    std::vector<const std::string*> group_keys;
    std::vector<bool> exact;  // by group: decided by the walk
    for (const auto& [key, members] : groups) {
        group_list.push_back(&members);
        group_keys.push_back(&key);
        exact.push_back(exact_keys.count(key) != 0);
    }
    std::map<std::string, std::string> file_digest;
    for (const auto& [path, text] : files) {
        file_digest[path] = base::Sha256Hex(text.text);
    }
    // A group the cache knows needs neither the preprocessor nor the parser.
    std::vector<std::string> group_cache_key(group_list.size());
    std::vector<std::optional<CachedStage>> group_cached(group_list.size());
    if (cache != nullptr) {
        base::Sha256 run_digest;
        run_digest.Update(CacheKeyPrefix()).Update("bundle\n");
        for (std::size_t g = 0; g < group_list.size(); ++g) {
            const StageJob& first = jobs[group_list[g]->front()];
            if (!blocked(first)) {
                group_cache_key[g] = StageCacheKey(*group_keys[g], file_digest[first.file]);
                run_digest.Update(group_cache_key[g]).Update("\n");
            }
        }
        bundle.emplace(*cache, run_digest.FinishHex(), lineage);
        for (std::size_t g = 0; g < group_list.size(); ++g) {
            if (!group_cache_key[g].empty()) {
                if (std::optional<std::string> payload = bundle->Load(group_cache_key[g])) {
                    // One without the cost this validation wants answers nothing: the stage is
                    // parsed again and the entry replaced.
                    std::optional<CachedStage> cached = DecodeCachedStage(*payload);
                    if (cached && (cached->outcome.has_cost || !options.static_costs)) {
                        group_cached[g] = std::move(cached);
                    }
                }
            }
        }
    }
    auto hash_group = [&](std::size_t g) {
        return !blocked(jobs[group_list[g]->front()]) && !group_cached[g] && !exact[g];
    };
    for (std::size_t g = 0; g < group_list.size(); ++g) {
        if (hash_group(g)) {  // (a pool forks only for an item it runs)
            warm_up();
            break;
        }
    }
    const std::vector<WorkerItemResult> hashed = RunInWorkerProcesses(
            group_list.size(), options.jobs, GlslangLimits(),
            [&](std::size_t g, const ProgressNote&) {
                StageJob& first = jobs[group_list[g]->front()];
                HashStage(first);
                return first.hash + " " + first.digest;
            },
            hash_group);
    std::map<std::string, std::string> preprocess_errors;  // key → internal compiler error
    for (std::size_t g = 0; g < group_list.size(); ++g) {
        const std::vector<std::size_t>& members = *group_list[g];
        StageJob& first = jobs[members.front()];
        if (blocked(first)) {
            first.key = first.file + "|unusable";
        } else if (group_cached[g]) {
            first.hash = group_cached[g]->hash;
            first.digest = group_cached[g]->digest;
            first.key = first.file + "|" + first.hash;
        } else if (exact[g]) {
            // What decides the group's preprocessed text exactly stands for the text.
            first.digest = base::Sha256Hex(*group_keys[g] + "\n" + file_digest[first.file]);
            first.hash = first.digest.substr(0, 16);
            first.key = first.file + "|" + first.hash;
        } else if (hashed[g].failure == WorkerFailure::kNone) {
            const std::size_t space = hashed[g].payload.find(' ');
            first.hash = hashed[g].payload.substr(0, space);
            first.digest = hashed[g].payload.substr(space + 1);
            first.key = first.file + "|" + first.hash;
        } else {
            first.hash = fmt::format("failed-{}", g);
            first.key = first.file + "|" + first.hash;
            preprocess_errors[first.key] =
                    InternalCompilerError(hashed[g], "preprocessing this stage");
            report.internal_errors = true;
        }
        for (std::size_t i : members) {
            jobs[i].hash = first.hash;
            jobs[i].digest = first.digest;
            jobs[i].key = first.key;
        }
    }

    // 2. The distinct stage programs.
    std::map<std::string, std::size_t> program_index;
    std::vector<const StageJob*> representative;
    for (const StageJob& job : jobs) {
        auto [it, inserted] = program_index.emplace(job.key, report.stage_programs.size());
        if (inserted) {
            StageProgram program;
            program.stage = job.stage;
            program.target = job.target;
            program.file = job.file;
            program.hash = job.hash;
            program.defines = job.defines;
            report.stage_programs.push_back(std::move(program));
            representative.push_back(&job);
        }
        report.stage_programs[it->second].variants.push_back(job.variant_id);
    }
    // Programs that are decided before glslang parses anything; the rest are decided by step 3.
    std::vector<bool> decided(report.stage_programs.size(), false);
    for (std::size_t i = 0; i < report.stage_programs.size(); ++i) {
        const StageJob& job = *representative[i];
        StageProgram& program = report.stage_programs[i];
        if (!job.source->ok) {
            program.diagnostics.push_back(MakeError(job.file, 0, 0, "cannot read shader file"));
            decided[i] = true;
        } else if (!job.source->text_errors.empty()) {
            program.diagnostics = job.source->text_errors;
            decided[i] = true;
        } else if (auto error = preprocess_errors.find(job.key); error != preprocess_errors.end()) {
            program.diagnostics.push_back(MakeError(job.file, 0, 0, error->second));
            decided[i] = true;
        }
    }
    // Programs decided by glslang's own verdict (from the cache, or parsed in step 3), not by an
    // internal compiler error: the ones the cache may keep.
    std::vector<bool> keepable(report.stage_programs.size(), false);
    for (std::size_t g = 0; g < group_list.size(); ++g) {
        const std::size_t index = program_index[jobs[group_list[g]->front()].key];
        if (group_cached[g] && !decided[index]) {
            StageProgram& program = report.stage_programs[index];
            program.valid = group_cached[g]->outcome.valid;
            program.diagnostics = group_cached[g]->outcome.diagnostics;
            program.cost = group_cached[g]->outcome.cost;
            decided[index] = true;
            keepable[index] = true;
        }
    }

    // 3. Parse and link each distinct (vertex, fragment) pair in a worker. A worker parses both
    // stages of its pair and hands the parses straight to the link (a glslang tree is finalised
    // by the one program that links it); the first report of a stage program decides it.
    struct LinkJob {
        std::size_t vertex = 0;
        std::size_t fragment = 0;
        bool linked = false;
        std::vector<Diagnostic> diagnostics;
        std::string cache_key;  // "" when the cache is off or a stage has no digest
        bool cached = false;    // decided by the cache
    };
    // In the order of their stages, so that the links of one vertex stage are next to each other
    // and mostly go to one worker, which parses that stage once for all of them (kept parses,
    // WorkerLimits::contiguous_shares).
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> link_index;
    for (std::size_t v = 0; v < jobs.size() / 2; ++v) {
        link_index.emplace(
                std::make_pair(program_index[jobs[2 * v].key], program_index[jobs[2 * v + 1].key]),
                0);
    }
    std::vector<LinkJob> links;
    for (auto& [stages, index] : link_index) {
        index = links.size();
        links.push_back(LinkJob{stages.first, stages.second, false, {}, {}, false});
    }
    std::vector<std::size_t> verdict_link(jobs.size() / 2);
    for (std::size_t v = 0; v < jobs.size() / 2; ++v) {
        verdict_link[v] = link_index.at(
                std::make_pair(program_index[jobs[2 * v].key], program_index[jobs[2 * v + 1].key]));
    }
    // Which stage programs this process (a worker, after fork) has already reported, and the
    // parses it keeps for later links.
    std::vector<bool> reported(report.stage_programs.size(), false);
    KeptParses kept;
    kept.uses.assign(report.stage_programs.size(), 0);
    // A decided stage that is invalid: no link with it can succeed, so none is attempted.
    auto broken = [&](std::size_t index) {
        return decided[index] && !report.stage_programs[index].valid;
    };
    // Links of two stages the cache decided valid: the cache may know the link too.
    if (cache != nullptr) {
        for (LinkJob& link : links) {
            const StageJob& vertex = *representative[link.vertex];
            const StageJob& fragment = *representative[link.fragment];
            if (vertex.digest.empty() || fragment.digest.empty()) {
                continue;
            }
            link.cache_key = LinkCacheKey(vertex, fragment);
            if (!decided[link.vertex] || !decided[link.fragment] ||
                !report.stage_programs[link.vertex].valid ||
                !report.stage_programs[link.fragment].valid) {
                continue;
            }
            if (std::optional<std::string> payload = bundle->Load(link.cache_key)) {
                // One that does not decode is recomputed below, and the entry replaced.
                if (std::optional<LinkResult> outcome = DecodeLink(*payload)) {
                    link.linked = outcome->ok;
                    link.diagnostics = std::move(outcome->diagnostics);
                    link.cached = true;
                }
            }
        }
    }
    auto input_of = [&](std::size_t index) {
        const StageJob& job = *representative[index];
        GlslangStageInput input{job.file,   job.source->text, job.stage,
                                job.target, job.defines,      job.limits};
        input.skipped_lines = &job.skipped;
        return input;
    };
    auto link_runs = [&](std::size_t i) {
        // Skipped when the cache decided it, or when it can neither link nor decide a stage: a
        // stage that crashed glslang would only crash it again.
        const LinkJob& link = links[i];
        return !link.cached && !((broken(link.vertex) || broken(link.fragment)) &&
                                 decided[link.vertex] && decided[link.fragment]);
    };
    bool any_link_runs = false;
    for (std::size_t i = 0; i < links.size(); ++i) {
        if (link_runs(i)) {
            any_link_runs = true;
            ++kept.uses[links[i].vertex];
            ++kept.uses[links[i].fragment];
        }
    }
    if (any_link_runs) {
        warm_up();  // each target's tables once, before the workers fork
    }
    finish_warming();
    RunInWorkerProcesses(
            links.size(), options.jobs, GlslangLimits(),
            [&](std::size_t i, const ProgressNote& note) -> std::string {
                // In a worker, `decided` is the parent's state when the worker was forked.
                const LinkJob& link = links[i];
                if (broken(link.vertex) || broken(link.fragment)) {
                    // Nothing to link; parse only what is undecided and not yet reported.
                    for (std::size_t index : {link.vertex, link.fragment}) {
                        if (!decided[index] && !reported[index]) {
                            note(fmt::format("P{}", index));
                            note(EncodeStage(index, ParseStage(input_of(index)),
                                             options.static_costs));
                            reported[index] = true;
                        }
                    }
                    return {};
                }
                return ParseAndLink({{link.vertex, input_of(link.vertex)},
                                     {link.fragment, input_of(link.fragment)}},
                                    note, options.static_costs, &reported, &kept);
            },
            link_runs,
            [&](std::size_t i, const WorkerItemResult& result) {
                if (links[i].cached) {
                    return;  // skipped: the cache's outcome stands
                }
                for (auto& [index, outcome] : DecodeStages(result.notes, report.stage_programs)) {
                    if (!decided[index]) {
                        keepable[index] =
                                TakeStageReport(std::move(outcome), report.stage_programs[index],
                                                &report.internal_errors);
                        decided[index] = true;
                    }
                }
                LinkJob& link = links[i];
                report.internal_errors =
                        report.internal_errors || (result.failure != WorkerFailure::kNone &&
                                                   result.failure != WorkerFailure::kSkipped);
                bool glslangs_verdict = false;
                const LinkResult outcome = LinkOutcome(
                        result, representative[link.fragment]->file,
                        [&](std::size_t index, const std::string& message) {
                            StageProgram& program = report.stage_programs[index];
                            program.valid = false;
                            program.diagnostics = {MakeError(program.file, 0, 0, message)};
                            decided[index] = true;
                        },
                        &glslangs_verdict);
                report.internal_errors =
                        report.internal_errors || (!glslangs_verdict && !result.payload.empty());
                link.linked = outcome.ok;
                link.diagnostics = outcome.diagnostics;
                if (cache != nullptr && !link.cache_key.empty() && glslangs_verdict) {
                    bundle->Store(link.cache_key, result.payload);
                }
            });
    if (cache != nullptr) {
        for (std::size_t g = 0; g < group_list.size(); ++g) {
            const StageJob& first = jobs[group_list[g]->front()];
            const std::size_t index = program_index[first.key];
            if (!group_cache_key[g].empty() && !group_cached[g] && keepable[index]) {
                bundle->Store(group_cache_key[g],
                              EncodeCachedStage(
                                      report.stage_programs[index], first.digest,
                                      options.static_costs || !report.stage_programs[index].valid));
            }
        }
        bundle->Save();
        if (cache->Stats().stored > stored_before) {
            cache->Trim();
        }
    }
    for (LinkJob& link : links) {
        link.linked = link.linked && report.stage_programs[link.vertex].valid &&
                      report.stage_programs[link.fragment].valid;
    }
    report.links = static_cast<int>(links.size());

    // 4. One verdict per variant and target.
    for (std::size_t v = 0; v < jobs.size() / 2; ++v) {
        const StageJob& vjob = jobs[2 * v];
        const StageJob& fjob = jobs[2 * v + 1];
        const StageProgram& vs = report.stage_programs[program_index[vjob.key]];
        const StageProgram& fs = report.stage_programs[program_index[fjob.key]];
        const LinkJob& link = links[verdict_link[v]];
        VariantVerdict verdict;
        verdict.variant = *vjob.variant;
        verdict.target = vjob.target;
        verdict.vertex_hash = vs.hash;
        verdict.fragment_hash = fs.hash;
        verdict.valid = vs.valid && fs.valid && link.linked;
        verdict.vertex = RanStep(vs.valid, vs.diagnostics, vjob.variant_id);
        verdict.fragment = RanStep(fs.valid, fs.diagnostics, vjob.variant_id);
        // A link is attempted only when both stages parsed.
        verdict.link = vs.valid && fs.valid
                               ? RanStep(link.linked, link.diagnostics, vjob.variant_id)
                               : StepVerdict{StepStatus::kNotRun,
                                             Tagged(link.diagnostics, vjob.variant_id)};
        CollectStepDiagnostics(verdict);
        report.verdicts.push_back(std::move(verdict));
    }
    return report;
}

namespace {

// Which of `files` are linked together, as indices: a file whose stage no other file has is
// linked with each file of the other stage (one vertex stage shared by several fragment stages),
// so that an interface the two disagree on is found; with several files of both stages, a vertex
// and a fragment file of the same path but for the extension (water.vert, water.frag). A file in
// no pair is linked alone, since some errors (recursion, a missing main) appear only then.
// Before, only exactly one file of each stage was linked: `a.vert b.frag c.frag` validated each
// alone and called a b.frag that `a.vert` cannot feed valid.
std::vector<std::vector<std::size_t>> LinkGroups(const std::vector<ShaderFile>& files) {
    std::vector<std::size_t> vertex;
    std::vector<std::size_t> fragment;
    for (std::size_t i = 0; i < files.size(); ++i) {
        (files[i].stage == Stage::kVertex ? vertex : fragment).push_back(i);
    }
    auto stem = [&](std::size_t i) {
        return std::filesystem::path(files[i].path).replace_extension().string();
    };
    std::vector<std::vector<std::size_t>> groups;
    std::vector<bool> linked(files.size(), false);
    for (std::size_t v : vertex) {
        for (std::size_t f : fragment) {
            if (vertex.size() == 1 || fragment.size() == 1 || stem(v) == stem(f)) {
                groups.push_back({v, f});
                linked[v] = linked[f] = true;
            }
        }
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (!linked[i]) {
            groups.push_back({i});
        }
    }
    return groups;
}

}  // namespace

ValidationReport ValidateShaderFiles(const std::vector<ShaderFile>& files,
                                     const std::vector<std::string>& defines,
                                     const ShaderFileOptions& options) {
    ValidationReport report;
    std::vector<FileText> texts(files.size());
    for (std::size_t i = 0; i < files.size(); ++i) {
        texts[i] = ReadFile(files[i].path, files[i].path, defines);
        StageProgram program;
        program.stage = files[i].stage;
        program.file = files[i].path;
        program.defines = defines;
        program.variants.push_back(files[i].path);
        if (!texts[i].ok) {
            program.diagnostics.push_back(MakeError(
                    files[i].path, 0, 0,
                    fmt::format("cannot read shader file: {}; check the path", texts[i].error)));
        } else {
            program.hash = Fnv1a64Hex(texts[i].text);
            program.diagnostics = texts[i].text_errors;
        }
        report.stage_programs.push_back(std::move(program));
    }
    report.stage_slots = static_cast<int>(files.size());

    const std::vector<std::vector<std::size_t>> groups = LinkGroups(files);
    auto usable = [&](std::size_t i) { return texts[i].ok && texts[i].text_errors.empty(); };
    auto group_usable = [&](std::size_t g) {
        return std::all_of(groups[g].begin(), groups[g].end(), usable);
    };

    // The cache, as for configurations (one bundle per run, every result under its own key): a
    // group whose stages and link it knows needs no glslang at all, not even its warm-up.
    base::ContentCache* const cache = options.cache;
    const std::uint64_t stored_before = cache != nullptr ? cache->Stats().stored : 0;
    std::optional<base::CacheBundle> bundle;
    std::vector<std::string> stage_keys(files.size());
    std::vector<std::optional<CachedStage>> cached_stages(files.size());
    std::vector<std::string> link_keys(groups.size());
    std::vector<std::optional<LinkResult>> cached_links(groups.size());
    if (cache != nullptr) {
        base::Sha256 run_digest;
        run_digest.Update(CacheKeyPrefix()).Update("plain bundle\n");
        base::Sha256 lineage;
        lineage.Update(CacheKeyPrefix()).Update("plain lineage\n");
        for (std::size_t i = 0; i < files.size(); ++i) {
            if (usable(i)) {
                stage_keys[i] = StageCacheKey(
                        StageGroupKey(files[i].path, files[i].stage,
                                      PlainTargetLabel(options.target), options.limits, defines,
                                      MentionedIdentifiers(texts[i].text)),
                        base::Sha256Hex(texts[i].text));
                run_digest.Update(stage_keys[i]).Update("\n");
            }
            std::error_code ec;
            lineage.Update(std::filesystem::absolute(files[i].path, ec).string()).Update("\n");
        }
        bundle.emplace(*cache, run_digest.FinishHex(), lineage.FinishHex());
        for (std::size_t g = 0; g < groups.size(); ++g) {
            if (!group_usable(g)) {
                continue;
            }
            std::vector<std::string> keys;
            bool all_cached = true;
            bool all_valid = true;
            for (std::size_t i : groups[g]) {
                keys.push_back(stage_keys[i]);
                if (std::optional<std::string> payload = bundle->Load(stage_keys[i])) {
                    cached_stages[i] = DecodeCachedStage(*payload);
                    if (cached_stages[i] && !cached_stages[i]->outcome.has_cost) {
                        cached_stages[i].reset();  // plain files always get their cost
                    }
                }
                all_cached = all_cached && cached_stages[i].has_value();
                all_valid = all_valid && cached_stages[i] && cached_stages[i]->outcome.valid;
            }
            link_keys[g] = PlainLinkCacheKey(keys);
            if (all_cached && !all_valid) {
                cached_links[g] = LinkResult{};  // no link is attempted with an invalid stage
            } else if (all_cached) {
                if (std::optional<std::string> payload = bundle->Load(link_keys[g])) {
                    // One that does not decode is recomputed below, and the entry replaced.
                    cached_links[g] = DecodeLink(*payload);
                }
            }
        }
    }
    auto group_runs = [&](std::size_t g) { return group_usable(g) && !cached_links[g]; };
    for (std::size_t g = 0; g < groups.size(); ++g) {
        if (group_runs(g)) {
            WarmUpGlslang({GlslTarget::kEs100});
            break;
        }
    }
    std::vector<bool> reported(files.size(), false);
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            groups.size(), 2, GlslangLimits(),
            [&](std::size_t g, const ProgressNote& note) {
                std::vector<ItemStage> stages;
                for (std::size_t i : groups[g]) {
                    stages.push_back({i,
                                      {files[i].path, texts[i].text, files[i].stage, options.target,
                                       defines, options.limits, /*keep_version=*/true}});
                }
                return ParseAndLink(stages, note, true, &reported);
            },
            group_runs);
    for (std::size_t g = 0; g < groups.size(); ++g) {
        LinkResult link;
        if (cached_links[g]) {
            for (std::size_t i : groups[g]) {
                StageProgram& program = report.stage_programs[i];
                program.valid = cached_stages[i]->outcome.valid;
                program.diagnostics = cached_stages[i]->outcome.diagnostics;
                program.cost = cached_stages[i]->outcome.cost;
            }
            link = *cached_links[g];
        } else {
            for (auto& [index, outcome] : DecodeStages(results[g].notes, report.stage_programs)) {
                StageProgram& program = report.stage_programs[index];
                const bool own_verdict =
                        TakeStageReport(std::move(outcome), program, &report.internal_errors);
                if (own_verdict && bundle && !stage_keys[index].empty()) {
                    bundle->Store(stage_keys[index], EncodeCachedStage(program, "", true));
                }
            }
            bool glslangs_verdict = false;
            link = LinkOutcome(
                    results[g], files[groups[g].back()].path,
                    [&](std::size_t index, const std::string& message) {
                        report.stage_programs[index].diagnostics = {
                                MakeError(files[index].path, 0, 0, message)};
                    },
                    &glslangs_verdict);
            report.internal_errors =
                    report.internal_errors || (!glslangs_verdict && !results[g].payload.empty());
            if (bundle && !link_keys[g].empty() && glslangs_verdict) {
                bundle->Store(link_keys[g], results[g].payload);
            }
        }
        VariantVerdict verdict;
        std::vector<std::string> names;
        bool stages_ok = true;
        for (std::size_t i : groups[g]) {
            names.push_back(files[i].path);
            const StageProgram& program = report.stage_programs[i];
            stages_ok = stages_ok && program.valid;
            const bool is_vertex = files[i].stage == Stage::kVertex;
            (is_vertex ? verdict.vertex : verdict.fragment) = StepVerdict{
                    program.valid ? StepStatus::kValid : StepStatus::kInvalid, program.diagnostics};
            (is_vertex ? verdict.vertex_hash : verdict.fragment_hash) = program.hash;
        }
        verdict.variant = Variant{fmt::format("{}", fmt::join(names, "+")), defines};
        verdict.valid = stages_ok && link.ok;
        verdict.link = StepVerdict{stages_ok ? (link.ok ? StepStatus::kValid : StepStatus::kInvalid)
                                             : StepStatus::kNotRun,
                                   link.diagnostics};
        CollectStepDiagnostics(verdict);
        report.links += stages_ok ? 1 : 0;
        report.verdicts.push_back(std::move(verdict));
    }
    if (bundle) {
        bundle->Save();
        if (cache->Stats().stored > stored_before) {
            cache->Trim();
        }
    }
    return report;
}

const VariantVerdict* ValidationReport::Find(const Variant& variant, GlslTarget target) const {
    for (const VariantVerdict& v : verdicts) {
        if (v.target == target && v.variant == variant) {
            return &v;
        }
    }
    return nullptr;
}

ValidationReport ValidateVariants(const VariantConfig& config, const std::vector<Variant>& variants,
                                  const ValidationOptions& options, const ValidationReport& known) {
    std::vector<Variant> missing;
    for (const Variant& variant : variants) {
        const bool lacking = std::any_of(
                options.targets.begin(), options.targets.end(),
                [&](GlslTarget target) { return known.Find(variant, target) == nullptr; });
        if (lacking && std::find(missing.begin(), missing.end(), variant) == missing.end()) {
            missing.push_back(variant);
        }
    }
    ValidationReport report;
    if (!missing.empty()) {
        report = ValidateVariants(config, missing, options);
    }
    std::vector<VariantVerdict> verdicts;
    for (const Variant& variant : variants) {
        for (GlslTarget target : options.targets) {
            const VariantVerdict* found = known.Find(variant, target);
            if (found == nullptr) {
                found = report.Find(variant, target);
            }
            if (found != nullptr) {
                verdicts.push_back(*found);
            }
        }
    }
    report.verdicts = std::move(verdicts);
    return report;
}

}  // namespace tidepool
