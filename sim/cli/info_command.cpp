// `zenith info`: the version, the headless GL context and the star catalogue.
#include <fmt/format.h>

#include "commands.h"
#include "zenith/geo/stars.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/gl/error.h"
#include "zenith/version.h"

namespace zenith::cli {

Command AddInfoCommand(CLI::App& app) {
    CLI::App* info = app.add_subcommand(
        "info", "Versions, the headless GL context (ZENITH_GL=osmesa|egl), star catalogue");
    return {info, [] {
                fmt::print("zenith {}\n", kVersion);
                try {
                    const auto context = sky::gl::CreateHeadlessContextFromEnvironment();
                    fmt::print("GL context: {}\n", context->description());
                    const bool compute = sky::ResolveCloudPassStage(sky::CloudPassStage::kAuto) ==
                                         sky::CloudPassStage::kCompute;
                    fmt::print("clouds' passes: the {} stage (CloudSettings::pass_stage)\n",
                               compute ? "compute" : "fragment");
                } catch (const sky::gl::GlError& e) {
                    fmt::print("GL context: unavailable: {}\n", e.what());
                }
                try {
                    const auto catalog = geo::StarCatalog::Load();
                    fmt::print("star catalogue: {} stars to magnitude {:.1f}\n",
                               catalog.stars().size(), catalog.magnitude_limit());
                } catch (const geo::CatalogError& e) {
                    fmt::print("star catalogue: unavailable: {}\n", e.what());
                }
                return 0;
            }};
}

}  // namespace zenith::cli
