// The render's two kinds of unit. A configuration's unit: compiled in Mesa, an image per view
// (compared with the reference configuration's while in memory, written as PNG) and its coarse
// frames. A comparison's unit: both configurations timed pair by pair, then each one's passes.
// The render's threads run them (Results.cpp), and so does a second process beside the render
// (SharedUnits.cpp). Private to the runner library.
#pragma once

#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/PairedEstimate.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/runner/Results.h"

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "RenderProgress.h"

namespace tidepool::runner {

/// The reference configuration's images, by view, with their SSIM moments; filled by the thread
/// that renders the reference, read by every thread after.
class ReferenceImages {
public:
    void Keep(const std::string& view, const base::RgbaImage& image);

    /// `image` against the reference's at `view`, the way the report measures accuracy; nothing
    /// when the reference has no image there (yet) or the sizes differ.
    std::optional<base::ImageAccuracy> Compare(const std::string& view,
                                               const base::RgbaImage& image) const;

private:
    struct Kept {
        explicit Kept(const base::RgbaImage& from) : image(from), ssim(image) {}
        base::RgbaImage image;
        base::SsimReference ssim;
    };
    mutable std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const Kept>> views_;
};

/// One rendering thread's context, renderer and timer, and what it has compiled.
struct RenderWorker {
    std::unique_ptr<WaterRenderer> renderer;
    std::unique_ptr<FrameTimer> timer;
    std::map<std::size_t, DriverVerdict> prepared;  // by configuration index
};

/// The view a run times: RunOptions::timing_view, or the first view; null when there is none.
const CameraView* TimingView(const RunOptions& options);
/// The index of the configuration with RunOptions::reference_preset, when one has it.
std::optional<std::size_t> ReferenceConfiguration(const RunOptions& options);

/// The pairs a comparison's probe takes (ProbeComparison): the fewest an interval is computed
/// from, half the default minimum of 20 pairs.
inline constexpr int kProbePairs = base::kMinimumPairs;

/// Whether a run probes its comparisons early (RenderWorkOrder): when it has comparisons, its
/// rule's first look comes after kProbePairs pairs (a probe of them would be that look), and it
/// renders on one thread (with several, a comparison's rest could go to another thread than its
/// probe, and every pair of a comparison is timed on one thread).
bool ProbesComparisons(const RunOptions& options);

/// The order a run's units are taken in (RenderWorkOrder): the reference configuration, then
/// every comparison's probe (ProbesComparisons; in base::ProbeOrder), then the configurations
/// the comparisons time, in the comparisons' order, then every comparison, then the other
/// configurations. The render process takes units from the front, a second process from the end.
std::vector<WorkUnit> RunWorkOrder(const RunOptions& options);

/// Compiles configuration `i` in `w`'s context once; with `warm`, renders warm-up frames too
/// (llvmpipe compiles shader variants on first draw, which must not land in a timed frame).
const DriverVerdict& PrepareConfiguration(RenderWorker& w, const RunOptions& options, std::size_t i,
                                          bool warm);

/// What rendering a configuration's unit needs beside the thread's worker.
struct ImageUnitContext {
    const RunOptions& options;
    ReferenceImages& references;
    ProgressMeter* meter;  // none in a second process, whose progress the render's meter counts
    std::mutex& errors_mutex;
    std::vector<std::string>& write_errors;  // PNGs that could not be written
};

/// Renders configuration `i`'s unit into `r`: its driver verdict, an image per view (kept as the
/// reference's when `i` is the reference configuration) and its coarse frames. A configuration
/// that does not compile gets its verdict only. Failures are in `r` and `write_errors`.
void RenderConfigurationUnit(RenderWorker& w, const ImageUnitContext& context, std::size_t i,
                             ConfigurationResult& r);

/// The frames a configuration's unit counts for in the progress line: its views and coarse frames.
long FramesPerConfiguration(const RunOptions& options);

/// RunOptions::rule with `comparison`'s own verdict boundaries: the rule it is timed by.
base::StoppingRule ComparisonRule(const RunOptions& options, const TimedComparison& comparison);

/// Which part of a comparison TimeComparisonUnit times.
enum class ComparisonPart {
    kProbe,  // its first kProbePairs pairs (ProbeComparison) into `out.timing`, nothing more
    kRest,   // on from what `out.timing` holds (a probe's pairs, or none) to the rule's stop
};

/// Times comparison `out.comparison` on `w`: both configurations compiled and warmed, then for
/// kRest pairs until its ComparisonRule stops (on from a probe's, with both sides warmed again),
/// then RunOptions::pass_frames pairs of instrumented frames for each side's per-pass times; for
/// kProbe only the probe's pairs. `after_look` (may be empty) sees the timing after every look,
/// and after the probe. Sets `out.error` instead when there is no timing view or a side does not
/// compile in Mesa.
void TimeComparisonUnit(RenderWorker& w, const RunOptions& options, ComparisonResult& out,
                        const std::function<void(const ComparisonTiming& so_far)>& after_look,
                        ComparisonPart part = ComparisonPart::kRest);

}  // namespace tidepool::runner
