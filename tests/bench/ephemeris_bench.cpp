// Positions per second, single thread: Sun, Moon, planets, stars and the whole topocentric
// ephemeris.
// Baseline in the same process: ERFA's IAU 2006/2000A chain for the Sun (eraEpv00 + eraPnm06a +
// eraAb), the reference implementation the tests compare against. Report ratios, not absolutes
// (see BENCHMARKS.md).
#include <benchmark/benchmark.h>
#include <erfa.h>

#include <cmath>
#include <optional>

#include "zenith/geo/ephemeris.h"
#include "zenith/geo/moon.h"
#include "zenith/geo/planets.h"
#include "zenith/geo/refraction.h"
#include "zenith/geo/sun.h"

namespace {

using namespace zenith::geo;

constexpr double kStartJd = 2460409.0;  // 2024-04-08
constexpr double kStepDays = 0.0137;    // not commensurate with anything periodic

void BM_ErfaSunBaseline(benchmark::State& state) {
    double jd = kStartJd;
    for (auto _ : state) {
        double pvh[2][3], pvb[2][3], rnpb[3][3];
        eraEpv00(jd, 0.0, pvh, pvb);
        double p[3] = {-pvh[0][0], -pvh[0][1], -pvh[0][2]};
        double d = 0.0, u[3];
        eraPn(p, &d, u);
        double v[3] = {pvb[1][0] / 173.1446, pvb[1][1] / 173.1446, pvb[1][2] / 173.1446};
        double ppr[3];
        eraAb(u, v, d, std::sqrt(1.0 - eraPdp(v, v)), ppr);
        eraPnm06a(jd, 0.0, rnpb);
        double tod[3];
        eraRxp(rnpb, ppr, tod);
        benchmark::DoNotOptimize(tod);
        jd += kStepDays;
    }
}
BENCHMARK(BM_ErfaSunBaseline);

void BM_SunApparentTod(benchmark::State& state) {
    double jd = kStartJd;
    for (auto _ : state) {
        benchmark::DoNotOptimize(SunApparentTod(jd));
        jd += kStepDays;
    }
}
BENCHMARK(BM_SunApparentTod);

void BM_MoonApparentTod(benchmark::State& state) {
    double jd = kStartJd;
    for (auto _ : state) {
        benchmark::DoNotOptimize(MoonApparentTod(jd));
        jd += kStepDays;
    }
}
BENCHMARK(BM_MoonApparentTod);

// Sun + Moon + phase, topocentric, no stars, no planets: the per-frame call before planets.
void BM_EphemerisSunMoon(benchmark::State& state) {
    const Observer observer(47.26, 11.35, 3000.0);
    const Ephemeris ephemeris;
    EphemerisOptions options;
    options.planets = false;
    double jd = kStartJd;
    for (auto _ : state) {
        const Time t = TimeFromUtc(CivilFromJulianDate(jd));
        benchmark::DoNotOptimize(ephemeris.Compute(t, observer, options));
        jd += kStepDays;
    }
}
BENCHMARK(BM_EphemerisSunMoon);

// The same call with the default options, which add Mercury to Neptune (light time, apparent
// place, topocentric, magnitudes): the ratio to BM_EphemerisSunMoon is the planets' cost.
void BM_EphemerisSunMoonPlanets(benchmark::State& state) {
    const Observer observer(47.26, 11.35, 3000.0);
    const Ephemeris ephemeris;
    double jd = kStartJd;
    for (auto _ : state) {
        const Time t = TimeFromUtc(CivilFromJulianDate(jd));
        benchmark::DoNotOptimize(ephemeris.Compute(t, observer));
        jd += kStepDays;
    }
}
BENCHMARK(BM_EphemerisSunMoonPlanets);

// The planets alone, for the record.
void BM_PlanetsTopocentric(benchmark::State& state) {
    const Observer observer(47.26, 11.35, 3000.0);
    double jd = kStartJd;
    for (auto _ : state) {
        const Time t = TimeFromUtc(CivilFromJulianDate(jd));
        benchmark::DoNotOptimize(PlanetsTopocentric(t, observer));
        jd += kStepDays;
    }
}
BENCHMARK(BM_PlanetsTopocentric);

// Everything, with all stars to magnitude 6.5 reduced to ENU; items/s counts stars.
void BM_EphemerisWithStars(benchmark::State& state) {
    std::optional<StarCatalog> catalog;
    try {
        catalog = StarCatalog::Load(6.5);
    } catch (const CatalogError& e) {
        state.SkipWithError(e.what());
        return;
    }
    const Observer observer(47.26, 11.35, 3000.0);
    const Ephemeris ephemeris(&*catalog);
    EphemerisOptions options;
    options.star_min_elevation = -1.6;  // keep every star so the work is constant
    double jd = kStartJd;
    for (auto _ : state) {
        const Time t = TimeFromUtc(CivilFromJulianDate(jd));
        benchmark::DoNotOptimize(ephemeris.Compute(t, observer, options));
        jd += kStepDays;
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(catalog->stars().size()));
}
BENCHMARK(BM_EphemerisWithStars)->Unit(benchmark::kMillisecond);

}  // namespace

// The refraction table a frame draws the bodies with (traced once per height, then cached by
// sky::RefractionCache), against the Sun and Moon of a frame above.
void BM_RefractionTable(benchmark::State& state) {
    double height = 10000.0;
    for (auto _ : state) {
        const zenith::geo::RefractionTable table(zenith::geo::RefractionAir{}, height);
        benchmark::DoNotOptimize(table.horizon());
        height += 1.0;
    }
}
BENCHMARK(BM_RefractionTable)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
