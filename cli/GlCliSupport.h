// Pieces the GL commands (render, bench, run, stability, plan) share: backend, timing and
// Fourier flags, and the progress printer. Built into `tidepool-gl` only, so the
// `tidepool` front end never links the runner.
#pragma once

#include "tidepool/pipeline/Timing.h"
#include "tidepool/runner/FourierReflection.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Results.h"

#include <cstdio>
#include <string>

#include "CliSupport.h"

namespace tidepool::cli {

/// Parses --backend; on failure prints "error: --backend must be auto, egl or osmesa, not
/// 'TEXT'" and returns false.
bool ParseBackendOption(const std::string& text, runner::BackendKind* backend);

/// Adds --fourier-coefficients and --fourier-directions (REFLECTION_FOURIER) to `command`,
/// writing into `settings`.
void AddFourierOptions(CLI::App* command, runner::FourierSettings* settings);

/// Prints why `settings` cannot be used, naming the options, and returns false; true when they
/// can.
bool CheckFourierOptions(const runner::FourierSettings& settings);

/// The timing flags `render`, `bench` and `run` share (the one timing engine's settings).
using TimingFlags = pipeline::TimingSettings;

/// Adds --resolution, --min-pairs, --max-pairs, --coarse-frames, --warmup, --workers and
/// --threads to `command`, writing into `flags`.
void AddTimingFlags(CLI::App* command, TimingFlags* flags);

/// The most frames --coarse-frames or --warmup may ask for.
inline constexpr int kMaxFramesPerStep = 1000;

/// Prints why `flags` cannot be used, naming the option and its range, and returns false.
bool CheckTimingFlags(const TimingFlags& flags);

/// "42s" or "3m05s". Never fails.
std::string FormatDuration(double seconds);

/// A render progress callback printing to stderr: on a terminal one line rewritten in place
/// (FinishProgress ends it), in a log a plain line on every stage change and at most every 10
/// seconds. Never fails.
runner::ProgressCallback MakeProgressPrinter();

/// The same printer writing to `out`, as on a terminal when `terminal` (tests give it a file).
/// A plain line is printed on every change of stage, when 10 s have passed since the last one,
/// and once when the render is complete (all frames done, no ETA left): a render waiting for a
/// second process's last units is told so every half second and must not repeat the line.
runner::ProgressCallback MakeProgressPrinter(std::FILE* out, bool terminal);

/// Adds --progress-log FILE to `command`, writing into `path` (StderrProgressSink::OpenLog).
void AddProgressLogFlag(CLI::App* command, std::string* path);

/// Ends the line a terminal progress printer left open. Never fails.
void FinishProgress();

}  // namespace tidepool::cli
