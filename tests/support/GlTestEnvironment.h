// One GL context and the shipped variants.yaml for a whole gl test binary: creating a context
// costs more than most tests, and every test file needs both.
#pragma once

#include "tidepool/VariantConfig.h"
#include "tidepool/runner/GlBackend.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace tidepool::test_support {

struct GlTestEnvironment {
    std::unique_ptr<runner::GlContext> context;  // null when no GL context can be made
    std::optional<VariantConfig> config;         // the repository's variants.yaml
    std::string error;  // why context or config is missing (tests skip on it)
};

/// Made on first use (EGL surfaceless, else OSMesa) and kept for the binary's lifetime. Never
/// fails: what is missing is said in `error`.
inline GlTestEnvironment& SharedGlEnvironment() {
    static GlTestEnvironment environment = [] {
        GlTestEnvironment e;
        runner::GlContextResult created = runner::CreateGlContext(runner::BackendKind::kAuto);
        if (!created.context) {
            e.error = created.error;
            return e;
        }
        e.context = std::move(created.context);
        ConfigResult loaded =
                LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
        if (!loaded.config) {
            e.error = "variants.yaml does not load";
            return e;
        }
        e.config = std::move(loaded.config);
        return e;
    }();
    return environment;
}

}  // namespace tidepool::test_support
