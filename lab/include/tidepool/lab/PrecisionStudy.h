// The water fragment's math evaluated in float, double and emulated fp16 (mediump on hardware
// that has it: every operation rounds to half precision) over sweeps of its inputs, to name the
// expressions that lose precision at mediump and to check that the shaders' guarded forms do not.
#pragma once

#include "tidepool/stagefiles/StabilityFile.h"

#include <string>
#include <vector>

namespace tidepool::lab {

/// Rounds `value` to the nearest IEEE binary16 number (ties to even), with overflow to ±Inf past
/// 65504 and gradual underflow below 6.1e-5; NaN stays NaN. Never fails.
double RoundToHalf(double value);

/// A scalar that rounds to fp16 after every operation, as mediump arithmetic does on GPUs with
/// 16-bit ALUs (inputs are rounded when constructed, as a mediump varying or uniform is).
struct Half {
    double value = 0;
    Half() = default;
    /// Rounds `v` to fp16.
    Half(double v) : value(RoundToHalf(v)) {}  // NOLINT(google-explicit-constructor): a scalar
};
/// fp16 arithmetic: the exact result of each operation, rounded once.
Half operator+(Half a, Half b);
Half operator-(Half a, Half b);
Half operator-(Half a);
Half operator*(Half a, Half b);
Half operator/(Half a, Half b);
bool operator<(Half a, Half b);
bool operator>(Half a, Half b);

/// The accuracy of one shader expression over its sweep: a row of stability.json.
using PrecisionRow = stagefiles::PrecisionEntry;

/// Evaluates every expression of the study over its sweep (a few hundred thousand evaluations,
/// well under a second). Never fails.
std::vector<PrecisionRow> RunPrecisionStudy();

}  // namespace tidepool::lab
