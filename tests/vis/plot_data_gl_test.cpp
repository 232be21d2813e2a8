// zenith-plot's data against the renderer's LUTs: what is plotted and exported is what the GL
// renderer computed. Uses a headless GL context (OSMesa) for the LUTs but no X display: charts
// and images are built and read back, not drawn (the drawing is tests/vis/plot_cli_test.sh).
#include <gtest/gtest.h>
#include <vtkChartMatrix.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkXMLImageDataReader.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "luts.h"
#include "plots.h"

namespace zenith::vis {
namespace {

constexpr double kDeg = 0.017453292519943295;
// The chart samples the float LUT at texel centres through double uv arithmetic: only rounding.
constexpr double kTexelCentreTolerance = 1e-5;
// LUT (256 x 64, 40 steps) against the independent quadrature, transmittance above 0.05 and
// away from the horizon: the renderer's accuracy tests allow a few 1e-3.
constexpr double kReferenceTolerance = 5e-3;

class PlotDataTest : public ::testing::TestWithParam<std::string> {
  protected:
    static const Luts& LutsFor(const std::string& preset) {
        static std::map<std::string, Luts> cache;
        auto it = cache.find(preset);
        if (it == cache.end()) {
            Scene scene;
            scene.preset = preset;
            it = cache.emplace(preset, ComputeLuts(scene)).first;
        }
        return it->second;
    }
};

// The transmittance curves drawn (the chart's own tables) equal the renderer's texels where the
// sampled points are texel centres: each altitude is a texel row, each angle a texel column.
TEST_P(PlotDataTest, PlottedTransmittanceEqualsRendererLut) {
    const Luts& luts = LutsFor(GetParam());
    const sky::LutImage& lut = luts.transmittance;
    for (int y : {0, 9, 31, 63}) {
        TransmittancePlotOptions options;
        double r = 0.0, mu = 0.0;
        TransmittanceTexelRMu(luts, 0, y, &r, &mu);
        options.altitudes_km = {(r - luts.atmosphere.bottom_radius) / 1000.0};
        options.zeniths_deg = {};
        // The last column is the horizon itself, where the round trip through the angle decides
        // whether the ray grazes the ground: left out.
        for (int x = 0; x < lut.size.x - 1; x += 5) {
            double rx = 0.0, mux = 0.0;
            TransmittanceTexelRMu(luts, x, y, &rx, &mux);
            options.zenith_samples_deg.push_back(std::acos(mux) / kDeg);
        }
        const auto charts = MakeTransmittanceCharts(luts, options);
        const std::vector<vtkTable*> tables = ChartTables(charts, 0, false);
        ASSERT_EQ(tables.size(), 1u);
        vtkTable* table = tables[0];
        // The LUT holds only rays that miss the ground, so every sample is plotted.
        ASSERT_EQ(table->GetNumberOfRows(),
                  static_cast<vtkIdType>(options.zenith_samples_deg.size()));
        for (vtkIdType row = 0; row < table->GetNumberOfRows(); ++row) {
            const int x = static_cast<int>(row) * 5;
            const glm::vec4 texel = lut.at(x, y);
            for (int c = 0; c < 3; ++c) {
                const double plotted = table->GetValue(row, c + 1).ToDouble();
                EXPECT_NEAR(plotted, texel[c], kTexelCentreTolerance)
                    << GetParam() << " texel (" << x << ", " << y << ") channel " << c << " zenith "
                    << table->GetValue(row, 0).ToDouble() << " deg";
            }
        }
    }
}

// Between texels the curve is the renderer's lookup, and it agrees with the independent
// reference (no LUT): the physics check the overlay makes visible.
TEST_P(PlotDataTest, PlottedTransmittanceAgreesWithReference) {
    const Luts& luts = LutsFor(GetParam());
    TransmittancePlotOptions options;
    options.altitudes_km = {0.0, 7.3, 30.0};
    options.zeniths_deg = {0.0, 45.0, 80.0};
    options.zenith_samples_deg = {0.0, 13.0, 33.3, 55.0, 70.0, 80.0};
    options.altitude_samples_km = {0.0, 1.7, 12.0, 40.0, 80.0};
    options.reference = true;
    const auto charts = MakeTransmittanceCharts(luts, options);
    int compared = 0;
    for (int column : {0, 1}) {
        const auto lines = ChartTables(charts, column, false);
        const auto points = ChartTables(charts, column, true);
        ASSERT_EQ(lines.size(), 3u);
        ASSERT_EQ(points.size(), 3u);
        for (std::size_t i = 0; i < lines.size(); ++i) {
            for (vtkIdType row = 0; row < lines[i]->GetNumberOfRows(); ++row) {
                const double x = lines[i]->GetValue(row, 0).ToDouble();
                for (vtkIdType ref_row = 0; ref_row < points[i]->GetNumberOfRows(); ++ref_row) {
                    if (std::abs(points[i]->GetValue(ref_row, 0).ToDouble() - x) > 1e-9) continue;
                    for (int c = 1; c <= 3; ++c) {
                        const double reference = points[i]->GetValue(ref_row, c).ToDouble();
                        if (!(reference > 0.05)) continue;
                        ++compared;
                        EXPECT_NEAR(lines[i]->GetValue(row, c).ToDouble(), reference,
                                    kReferenceTolerance)
                            << GetParam() << " chart " << column << " curve " << i << " x " << x;
                    }
                }
            }
        }
    }
    EXPECT_GT(compared, 20) << "too few points where the chart and the reference share x";
}

// Every LUT written as .vti and read back holds the renderer's texels exactly (float32, binary).
TEST_P(PlotDataTest, VtiRoundTripsEveryLut) {
    const Luts& luts = LutsFor(GetParam());
    const std::filesystem::path dir =
        std::filesystem::path(ZENITH_BINARY_DIR) / "tests" / "vis_vti" / GetParam();
    std::filesystem::create_directories(dir);
    for (LutKind kind : kAllLuts) {
        const std::filesystem::path file = dir / (std::string(LutName(kind)) + ".vti");
        WriteVti(LutImageData(luts, kind), file);
        auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
        reader->SetFileName(file.c_str());
        reader->Update();
        vtkImageData* image = reader->GetOutput();
        const sky::LutImage& lut = luts.Image(kind);
        int dims[3];
        image->GetDimensions(dims);
        ASSERT_EQ(dims[0], lut.size.x) << file;
        ASSERT_EQ(dims[1], lut.size.y) << file;
        ASSERT_EQ(dims[2], lut.size.z) << file;
        vtkDataArray* rgba = image->GetPointData()->GetArray("rgba");
        ASSERT_NE(rgba, nullptr) << file;
        ASSERT_EQ(rgba->GetNumberOfComponents(), 4);
        ASSERT_EQ(rgba->GetNumberOfTuples(), static_cast<vtkIdType>(lut.texels.size()));
        std::size_t mismatches = 0;
        for (std::size_t i = 0; i < lut.texels.size(); ++i) {
            for (int c = 0; c < 4; ++c) {
                const double read = rgba->GetComponent(static_cast<vtkIdType>(i), c);
                if (!(read == static_cast<double>(lut.texels[i][c]))) ++mismatches;
            }
        }
        EXPECT_EQ(mismatches, 0u) << file;
        EXPECT_NE(image->GetPointData()->GetScalars(), nullptr) << file << ": no named scalars";
    }
}

// The texel -> physical mappings exported and used for axes invert the renderer's forward
// lookups: sampling at a texel's physical coordinates returns that texel.
TEST_P(PlotDataTest, PhysicalCoordinatesOfTexelsSampleTheTexel) {
    const Luts& luts = LutsFor(GetParam());
    for (int y : {0, 17, 31}) {
        for (int x : {0, 5, 16, 31}) {
            double mu_s = 0.0, h = 0.0;
            MultipleScatteringTexelMuSAltitude(luts, x, y, &mu_s, &h);
            const glm::dvec3 sampled = SampleMultipleScattering(luts, h, mu_s);
            const glm::vec4 texel = luts.multiple_scattering.at(x, y);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(sampled[c], texel[c], 1e-6 + 1e-5 * std::abs(texel[c]))
                    << "multiple scattering (" << x << ", " << y << ")";
            }
        }
    }
    for (int y : {0, 30, 50, 70, 99}) {
        for (int x : {0, 50, 199}) {
            double view_zenith = 0.0, azimuth = 0.0;
            SkyViewTexelAngles(luts, x, y, &view_zenith, &azimuth);
            const glm::dvec3 sampled = SampleSkyView(luts, view_zenith, azimuth);
            const glm::vec4 texel = luts.sky_view.at(x, y);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(sampled[c], texel[c], 1e-3 * std::abs(texel[c]) + 1e-6)
                    << "sky view (" << x << ", " << y << ")";
            }
        }
    }
    for (int x : {0, 20, 63}) {
        const glm::dvec3 sampled = SampleIrradiance(luts, IrradianceTexelMuS(luts, x));
        EXPECT_NEAR(sampled.g, luts.irradiance.at(x, 0).g,
                    1e-5 * luts.irradiance.at(x, 0).g + 1e-9);
    }
    for (int z : {0, 8, 31}) {
        double horizontal = 0.0, vertical = 0.0;
        AerialPerspectiveCellAngles(luts, 3, 29, &horizontal, &vertical);
        const glm::dvec4 sampled = SampleAerialPerspectiveSlice(luts, z, horizontal, vertical);
        const glm::vec4 texel = luts.aerial_perspective.at(3, 29, z);
        EXPECT_NEAR(sampled.a, texel.a, 1e-5);
        EXPECT_NEAR(sampled.g, texel.g, 1e-5 * std::abs(texel.g) + 1e-6);
    }
}

// Slices are NaN exactly where the LUT has no data (transmittance along rays into the ground).
TEST_P(PlotDataTest, TransmittanceSliceIsBlankBelowTheHorizon) {
    const Luts& luts = LutsFor(GetParam());
    const Slice s = MakeSlice(luts, LutKind::kTransmittance, Channel::kG, 0, 181, 11);
    for (int j = 0; j < s.height; ++j) {
        const double altitude = (s.y0 + j * s.dy) * 1000.0;
        const double horizon_deg = HorizonZenithAngle(luts, altitude) / kDeg;
        for (int i = 0; i < s.width; ++i) {
            const double zenith = s.x0 + i * s.dx;
            const double v = s.values[static_cast<std::size_t>(j * s.width + i)];
            if (zenith < horizon_deg - 0.5) {
                EXPECT_TRUE(v >= 0.0 && v <= 1.0) << zenith;
            }
            if (zenith > horizon_deg + 0.5) {
                EXPECT_TRUE(std::isnan(v)) << zenith;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Presets, PlotDataTest, ::testing::Values("earth", "mars"));

}  // namespace
}  // namespace zenith::vis
