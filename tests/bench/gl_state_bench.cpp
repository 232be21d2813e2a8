// The cost of the GL state contract (sky/src/gl/state_guard.h): one guard that saves, sets and
// restores (~150 glGet and ~130 set calls) against one that only sets, and a whole 1280x720
// frame (Update + Render, two guards) with and without preserving the host's state.
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <memory>

#include "daytime_frame.h"
#include "gl/state_guard.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"

namespace {

using namespace zenith::sky;

using Fixture = bench::DaytimeFrame;
using bench::Shared;

// Save, set and restore: what each renderer entry point costs a host on top of its passes.
void BM_GuardPreserving(benchmark::State& state) {
    Shared();
    for (auto _ : state) {
        const gl::StateGuard guard(true);
        benchmark::ClobberMemory();
    }
}
BENCHMARK(BM_GuardPreserving)->Unit(benchmark::kMicrosecond);

// Set only (SkySystemSettings::preserve_gl_state = false).
void BM_GuardSettingOnly(benchmark::State& state) {
    Shared();
    for (auto _ : state) {
        const gl::StateGuard guard(false);
        benchmark::ClobberMemory();
    }
}
BENCHMARK(BM_GuardSettingOnly)->Unit(benchmark::kMicrosecond);

void Frame(benchmark::State& state, bool preserve) {
    Fixture& f = Shared();
    f.renderer.set_preserve_gl_state(preserve);
    for (auto _ : state) {
        f.renderer.Update(f.scene, f.view);
        f.renderer.Render(f.target);
        glFinish();
    }
    f.renderer.set_preserve_gl_state(true);
}
void BM_Frame720pPreserving(benchmark::State& state) { Frame(state, true); }
void BM_Frame720pSettingOnly(benchmark::State& state) { Frame(state, false); }
BENCHMARK(BM_Frame720pPreserving)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame720pSettingOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
