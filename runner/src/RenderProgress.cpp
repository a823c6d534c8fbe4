// The render's order of work and its progress line (RenderProgress.h).
#include "RenderProgress.h"

#include "tidepool/base/PairedEstimate.h"
#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <utility>

namespace tidepool::runner {
namespace {

double SecondsOf(ProgressMeter::Clock::duration duration) {
    return std::chrono::duration<double>(duration).count();
}

// How many frames' worth of evidence the other kind's rate counts for while a kind has measured
// none: about 6 configurations' images, the first block of images after the first comparison.
// It fades as the kind's own frames are measured. (150 frames, when images came after every
// comparison, kept image frames priced like timed frames for the first minute of a loaded run:
// its ETA was 21% short.)
constexpr double kPriorFrames = 40.0;

}  // namespace

double SecondsToFinish(double work, double threads, std::optional<double> helper_joins_in,
                       double own) {
    threads = std::max(threads, 1.0);
    work = std::max(work, 0.0);
    own = std::clamp(own, 0.0, work);
    if (!helper_joins_in) {
        return work / threads;
    }
    const double alone = std::max(*helper_joins_in, 0.0);
    if (work <= alone * threads) {
        return work / threads;
    }
    // Shared from the join in proportion to threads, unless the second process would need more
    // than the units it may take: then this process's own work sets the end.
    return std::max(alone + (work - alone * threads) / (threads + 1), own / threads);
}

double ContendedFramesCost(double contended_share, double core_share) {
    const double share = std::max(contended_share, 0.0);
    const double core = core_share > 0 && core_share <= 1 ? core_share : kDefaultCoreShare;
    return (1.0 + share * (1.0 + core)) / (1.0 + share);
}

std::vector<WorkUnit> RenderWorkOrder(std::size_t comparisons, std::size_t configurations,
                                      std::optional<std::size_t> first,
                                      const std::vector<std::size_t>& early, bool probes) {
    std::vector<std::size_t> order(configurations);
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(20161));
    std::vector<WorkUnit> units;
    units.reserve((probes ? 2 : 1) * comparisons + configurations);
    auto take = [&](std::size_t i) {
        const auto at = std::find(order.begin(), order.end(), i);
        if (at != order.end()) {
            order.erase(at);
            units.push_back({false, i});
        }
    };
    if (first) {
        take(*first);
    }
    if (probes) {
        for (std::size_t k : base::ProbeOrder(comparisons)) {
            units.push_back({true, k, true});
        }
    }
    for (std::size_t i : early) {
        take(i);
    }
    for (std::size_t k = 0; k < comparisons; ++k) {
        units.push_back({true, k});
    }
    for (std::size_t i : order) {
        units.push_back({false, i});
    }
    return units;
}

void ProgressMeter::AddExpected(Kind kind, long frames) {
    std::lock_guard<std::mutex> lock(mutex_);
    kinds_[kind].total += frames;
}

void ProgressMeter::AddComparisons(std::size_t count, long guess) {
    std::lock_guard<std::mutex> lock(mutex_);
    comparison_guess_ = guess;
    comparison_frames_.assign(count, guess);
    first_guess_frames_.assign(count, 0);
    comparison_state_.assign(count, ComparisonState::kWaiting);
    comparison_done_.assign(count, 0);
    SumComparisons();
}

void ProgressMeter::ComparisonConfigurations(std::size_t k, std::size_t baseline,
                                             std::size_t candidate) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (comparison_configurations_.size() < comparison_frames_.size()) {
        const std::size_t none = static_cast<std::size_t>(-1);
        comparison_configurations_.resize(comparison_frames_.size(), {none, none});
    }
    if (k < comparison_configurations_.size()) {
        comparison_configurations_[k] = {baseline, candidate};
    }
}

void ProgressMeter::ComparisonCostPrior(double ratio) {
    if (!(ratio > 0) || !std::isfinite(ratio)) {
        return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    cost_prior_ = ratio;
}

void ProgressMeter::ConfigurationCost(std::size_t i, double seconds) {
    if (!(seconds > 0) || !std::isfinite(seconds)) {
        return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    configuration_cost_[i] = seconds;
}

void ProgressMeter::StepComparison(std::size_t k, const std::string& what, long frames,
                                   Clock::time_point now) {
    std::lock_guard<std::mutex> lock(mutex_);
    StepLocked(kComparison, what, frames, now, k);
}

void ProgressMeter::ComparisonExpects(std::size_t k, long frames, bool finished) {
    std::lock_guard<std::mutex> lock(mutex_);
    comparison_frames_[k] = frames;
    comparison_state_[k] = finished ? ComparisonState::kFinished : ComparisonState::kRunning;
    if (!finished && first_guess_frames_[k] == 0) {
        first_guess_frames_[k] = frames;
    }
    ExpectWaiting();
}

void ProgressMeter::ExpectWaiting() {
    // The guess: the mean of the first guesses of the comparisons that have looked; before any
    // has, the first guess. (A fixed guess of 60 pairs was short under load on one host, where
    // comparisons took 52 to 88 pairs on average, and nearly three times too long on a faster
    // one, where most stopped at the minimum 20.)
    double guess = static_cast<double>(comparison_guess_);
    double first_sum = 0;
    double first_count = 0;
    for (long f : first_guess_frames_) {
        if (f > 0) {
            first_sum += static_cast<double>(f);
            first_count += 1;
        }
    }
    if (first_count > 0) {
        guess = first_sum / first_count;
    }
    // The mean, shrunk towards the guess: the ETA needs the sum of what the waiting
    // comparisons will take, and the mean is what a sum grows by. (The median, used before,
    // fell short when most comparisons resolve at the minimum and a few near a boundary take
    // five times the pairs, and overshot when those few came first.)
    double frames_sum = kPriorComparisons * guess;
    double count = kPriorComparisons;
    for (std::size_t i = 0; i < comparison_frames_.size(); ++i) {
        if (comparison_state_[i] == ComparisonState::kFinished && comparison_frames_[i] > 0) {
            frames_sum += static_cast<double>(comparison_frames_[i]);
            count += 1;
        }
    }
    const long expected = std::lround(frames_sum / count);
    for (std::size_t i = 0; i < comparison_frames_.size(); ++i) {
        if (comparison_state_[i] == ComparisonState::kWaiting) {
            comparison_frames_[i] = expected;
        }
    }
    SumComparisons();
}

void ProgressMeter::Step(Kind kind, const std::string& what, long frames, Clock::time_point now) {
    std::lock_guard<std::mutex> lock(mutex_);
    StepLocked(kind, what, frames, now, std::nullopt);
}

void ProgressMeter::StepLocked(Kind kind, const std::string& what, long frames,
                               Clock::time_point now, std::optional<std::size_t> comparison) {
    if (decayed_to_ == Clock::time_point{}) {
        decayed_to_ = start_;
    }
    // Age what was measured so far, then add this step at full weight.
    const double age = std::max(0.0, SecondsOf(now - decayed_to_));
    const double keep = std::exp2(-age / kRateHalfLifeSeconds);
    for (KindState& k : kinds_) {
        k.recent_seconds *= keep;
        k.recent_frames *= keep;
    }
    priced_seconds_ *= keep;
    priced_estimate_ *= keep;
    decayed_to_ = std::max(decayed_to_, now);
    Clock::time_point& last =
            last_step_.try_emplace(std::this_thread::get_id(), start_).first->second;
    const double seconds = std::max(0.0, SecondsOf(now - last));
    KindState& k = kinds_[kind];
    k.recent_seconds += seconds;
    k.recent_frames += static_cast<double>(frames);
    last = now;
    k.done += frames;
    k.total = std::max(k.total, k.done);
    if (comparison && *comparison < comparison_done_.size()) {
        comparison_done_[*comparison] += frames;
        if (const std::optional<double> cost = CostOf(*comparison)) {
            priced_seconds_ += seconds;
            priced_estimate_ += *cost * static_cast<double>(frames);
        }
    }
    PublishLocked(kind == kComparison ? "comparisons" : "images", what, now);
}

void ProgressMeter::Waiting(const std::string& what, Clock::time_point now) {
    std::lock_guard<std::mutex> lock(mutex_);
    PublishLocked("waiting for", what, now);
}

std::optional<double> ProgressMeter::MeanConfigurationCost() const {
    if (configuration_cost_.empty()) {
        return std::nullopt;
    }
    double sum = 0;
    for (const auto& [configuration, seconds] : configuration_cost_) {
        sum += seconds;
    }
    return sum / static_cast<double>(configuration_cost_.size());
}

void ProgressMeter::PublishLocked(const char* stage, const std::string& what,
                                  Clock::time_point now) {
    // The units a second process has claimed are its work, not this meter's.
    const std::array<long, 2> helper_frames = HelperClaimedFrames();
    std::array<long, 2> totals{};
    for (std::size_t i = 0; i < kinds_.size(); ++i) {
        totals[i] = std::max(kinds_[i].total - helper_frames[i], kinds_[i].done);
    }
    state_.stage = stage;
    state_.configuration = what;
    state_.done = kinds_[0].done + kinds_[1].done;
    state_.total = totals[0] + totals[1];
    state_.elapsed_seconds = SecondsOf(now - start_);
    double done_seconds = 0;
    double left_seconds = 0;
    double own_seconds = 0;  // of left_seconds, in units this process has claimed
    for (std::size_t i = 0; i < kinds_.size(); ++i) {
        const double rate = SecondsPerFrame(i);
        done_seconds += rate * static_cast<double>(kinds_[i].done);
        if (i == kComparison && !comparison_configurations_.empty()) {
            const ComparisonSeconds comparisons = ComparisonSecondsLeft();
            left_seconds += comparisons.left;
            own_seconds += comparisons.owned;
        } else {
            left_seconds += rate * static_cast<double>(totals[i] - kinds_[i].done);
        }
    }
    const double threads = static_cast<double>(last_step_.size());
    // The second process finishes the units it is working on before it takes any other, and
    // the run ends no sooner than they do: this process collects their results at the end.
    const double helper_busy = HelperSecondsLeft(now);
    std::optional<double> joins = HelperJoinsIn(now);
    if (joins) {
        joins = std::max(*joins, helper_busy);
    }
    const double own_end = SecondsToFinish(left_seconds, threads, joins, own_seconds);
    state_.eta_seconds = std::max(own_end, helper_busy);
    // The work this process will do itself before its own end: its threads for that time. (Not
    // for the ETA: waiting for the second process is no work of this one, and counting it would
    // throw the percentage back when that process claims a long comparison.)
    const double left_here = own_end * threads;
    state_.percent = done_seconds + left_here > 0
                             ? 100.0 * done_seconds / (done_seconds + left_here)
                             : 100.0;
    state_.parts = {
            {"comparison_frames_done", static_cast<double>(kinds_[kComparison].done)},
            {"comparison_frames_left",
             static_cast<double>(totals[kComparison] - kinds_[kComparison].done)},
            {"comparison_seconds_per_frame", SecondsPerFrame(kComparison)},
            {"image_frames_done", static_cast<double>(kinds_[kImage].done)},
            {"image_frames_left", static_cast<double>(totals[kImage] - kinds_[kImage].done)},
            {"image_seconds_per_frame", SecondsPerFrame(kImage)},
            {"seconds_left", left_seconds},
            {"owned_seconds_left", own_seconds},
            {"threads", threads},
            {"calibration", Calibration()},
            {"second_process_busy_seconds", helper_busy},
            {"own_end_seconds", own_end},
    };
    if (const std::optional<double> cost = MeanConfigurationCost()) {
        state_.parts.emplace_back("mean_configuration_seconds", *cost);
    }
    if (joins) {
        state_.parts.emplace_back("second_process_joins_in_seconds", *joins);
    }
    if (callback_) {
        callback_(state_);
    }
}

void ProgressMeter::ShareUnits(const base::SharedClaims* claims, long frames_per_configuration,
                               std::size_t configurations,
                               std::chrono::milliseconds forecast_silence) {
    std::lock_guard<std::mutex> lock(mutex_);
    shared_ = claims;
    shared_frames_per_configuration_ = frames_per_configuration;
    shared_configurations_ = configurations;
    forecast_silence_ = forecast_silence;
    helper_seen_.assign(claims != nullptr ? claims->Size() : 0, std::nullopt);
}

// Seconds until the second process starts taking units: 0 while it takes them, its own forecast
// before, nothing when there is none, it has stopped, or it has not renewed its forecast for
// forecast_silence_ (mutex_ held).
std::optional<double> ProgressMeter::HelperJoinsIn(Clock::time_point now) const {
    if (shared_ == nullptr || shared_->HelperStopped()) {
        return std::nullopt;
    }
    if (shared_->HelperTaking()) {
        return 0.0;
    }
    const std::optional<Clock::time_point> expected = shared_->HelperExpectedAt();
    if (!expected || shared_->HelperSilentFor(forecast_silence_)) {
        return std::nullopt;  // no forecast, or its process may have died since it gave one
    }
    return std::max(0.0, SecondsOf(*expected - now));
}

// The frames of each kind in units the second process has claimed (mutex_ held): a configuration
// counts its image frames, a comparison the frames it is expected to take.
std::array<long, 2> ProgressMeter::HelperClaimedFrames() const {
    std::array<long, 2> frames{};
    if (shared_ == nullptr) {
        return frames;
    }
    for (std::size_t i = 0; i < shared_configurations_; ++i) {
        frames[kImage] += shared_->HelperHas(i) ? shared_frames_per_configuration_ : 0;
    }
    for (std::size_t k = 0; k < comparison_frames_.size(); ++k) {
        frames[kComparison] +=
                shared_->HelperHas(shared_configurations_ + k) ? comparison_frames_[k] : 0;
    }
    return frames;
}

// Seconds the second process still needs for the units it is working on (mutex_ held): each
// unit's expected seconds (a configuration's image frames at the image rate, a comparison's
// expected frames at its price; it times a comparison whole) less the time since this meter
// first saw it claimed, which is within a step of its claim.
double ProgressMeter::HelperSecondsLeft(Clock::time_point now) {
    if (shared_ == nullptr) {
        return 0.0;
    }
    double seconds = 0;
    const std::size_t units = std::min(shared_->Size(), helper_seen_.size());
    for (std::size_t unit = 0; unit < units; ++unit) {
        if (shared_->StateOf(unit) != base::SharedClaims::State::kHelperWorking) {
            continue;
        }
        std::optional<Clock::time_point>& seen = helper_seen_[unit];
        if (!seen) {
            seen = now;
        }
        double expected = 0;
        if (unit < shared_configurations_) {
            expected =
                    static_cast<double>(shared_frames_per_configuration_) * SecondsPerFrame(kImage);
        } else if (const std::size_t k = unit - shared_configurations_;
                   k < comparison_frames_.size()) {
            expected = static_cast<double>(comparison_frames_[k]) * PriceOf(k);
        }
        seconds += std::max(0.0, expected - SecondsOf(now - *seen));
    }
    return seconds;
}

RunProgress ProgressMeter::Last() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_;
}

// A kind's seconds per frame over its recent frames, shrunk towards a prior as if the prior were
// some frames already measured. The first frames of a kind are few and uneven (a Fourier variant
// costs several light ones; the reference configuration, whose images come first, is the
// heaviest), so alone they would throw the ETA about; the prior's weight fades as the kind's own
// frames are measured. The prior for image frames is kImageFrameCost times the mean cost of a
// timed frame of the configurations measured so far (ConfigurationCost), or, before any, the
// comparisons' recent rate; for comparison frames, the images' recent rate.
double ProgressMeter::SecondsPerFrame(std::size_t kind) const {
    const KindState& k = kinds_[kind];
    const KindState& other = kinds_[1 - kind];
    const double own = k.recent_frames > 0 ? k.recent_seconds / k.recent_frames : 0.0;
    double prior = 0;
    if (const std::optional<double> cost = MeanConfigurationCost(); kind == kImage && cost) {
        prior = kImageFrameCost * *cost;
    } else if (other.recent_frames > 0) {
        prior = other.recent_seconds / other.recent_frames;
    } else {
        return own;
    }
    const double weight =
            kPriorFrames * kPriorFrames / (kPriorFrames + static_cast<double>(k.done));
    return (k.recent_seconds + prior * weight) / (k.recent_frames + weight);
}

// The mean of comparison k's two configurations' costs, once both are known (mutex_ held).
std::optional<double> ProgressMeter::CostOf(std::size_t k) const {
    if (k >= comparison_configurations_.size()) {
        return std::nullopt;
    }
    const auto a = configuration_cost_.find(comparison_configurations_[k][0]);
    const auto b = configuration_cost_.find(comparison_configurations_[k][1]);
    if (a == configuration_cost_.end() || b == configuration_cost_.end()) {
        return std::nullopt;
    }
    return (a->second + b->second) / 2.0;
}

// Seconds comparison frames took per second of their price, recently (mutex_ held). A few
// seconds of prior at cost_prior_ keep the first look's warm-up from setting it alone.
double ProgressMeter::Calibration() const {
    constexpr double kPriorSeconds = 2.0;
    return (priced_seconds_ + kPriorSeconds * cost_prior_) / (priced_estimate_ + kPriorSeconds);
}

double ProgressMeter::PriceOf(std::size_t k) const {
    const std::optional<double> cost = CostOf(k);
    return cost ? *cost * Calibration() : SecondsPerFrame(kComparison);
}

ProgressMeter::ComparisonSeconds ProgressMeter::ComparisonSecondsLeft() const {
    ComparisonSeconds seconds;
    for (std::size_t k = 0; k < comparison_frames_.size(); ++k) {
        const std::size_t unit = shared_configurations_ + k;
        const bool helpers = shared_ != nullptr && shared_->HelperHas(unit);
        if (helpers || comparison_state_[k] == ComparisonState::kFinished) {
            continue;
        }
        const long left = std::max(0L, comparison_frames_[k] - comparison_done_[k]);
        const double left_seconds = static_cast<double>(left) * PriceOf(k);
        seconds.left += left_seconds;
        if (shared_ != nullptr && unit < shared_->Size() &&
            shared_->StateOf(unit) == base::SharedClaims::State::kOwner) {
            seconds.owned += left_seconds;
        }
    }
    return seconds;
}

// The comparison kind's total: the frames every comparison expects (mutex_ held).
void ProgressMeter::SumComparisons() {
    long total = 0;
    for (long frames : comparison_frames_) {
        total += frames;
    }
    kinds_[kComparison].total = std::max(total, kinds_[kComparison].done);
}

}  // namespace tidepool::runner
