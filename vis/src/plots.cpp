#include "plots.h"

#include <fmt/format.h>
#include <vtkAbstractContextItem.h>
#include <vtkActor.h>
#include <vtkArrowSource.h>
#include <vtkAxis.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkChartHistogram2D.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkColorLegend.h>
#include <vtkColorTransferFunction.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotLine.h>
#include <vtkPlotPoints.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyLine.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkTubeFilter.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "zenith/base/error.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/geo/observer.h"
#include "zenith/geo/time.h"
#include "zenith/track/flight_log.h"
#include "zenith/track/trajectory.h"

namespace zenith::vis {
namespace {

constexpr double kKm = 1000.0;
constexpr double kDeg = 0.017453292519943295;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Rgb8 {
    unsigned char r, g, b;
};
constexpr Rgb8 kChannelColours[3] = {{214, 39, 40}, {44, 160, 44}, {31, 119, 180}};
constexpr const char* kChannelNames[3] = {"R", "G", "B"};
constexpr int kLineStyles[] = {vtkPen::SOLID_LINE, vtkPen::DASH_LINE, vtkPen::DOT_LINE,
                               vtkPen::DASH_DOT_LINE, vtkPen::DASH_DOT_DOT_LINE};

vtkSmartPointer<vtkTable> CurveTable(const Curve& curve) {
    auto table = vtkSmartPointer<vtkTable>::New();
    auto x = vtkSmartPointer<vtkDoubleArray>::New();
    x->SetName("x");
    table->AddColumn(x);
    for (const char* name : kChannelNames) {
        auto column = vtkSmartPointer<vtkDoubleArray>::New();
        column->SetName(name);
        table->AddColumn(column);
    }
    table->SetNumberOfRows(static_cast<vtkIdType>(curve.x.size()));
    for (std::size_t i = 0; i < curve.x.size(); ++i) {
        const auto row = static_cast<vtkIdType>(i);
        table->SetValue(row, 0, curve.x[i]);
        for (int c = 0; c < 3; ++c) table->SetValue(row, c + 1, curve.rgb[i][c]);
    }
    return table;
}

void AddCurve(vtkChartXY* chart, const Curve& curve, int style_index, bool reference) {
    const vtkSmartPointer<vtkTable> table = CurveTable(curve);
    for (int c = 0; c < 3; ++c) {
        vtkPlot* plot = chart->AddPlot(reference ? vtkChart::POINTS : vtkChart::LINE);
        plot->SetInputData(table, 0, c + 1);
        plot->SetColor(kChannelColours[c].r, kChannelColours[c].g, kChannelColours[c].b, 255);
        plot->SetLabel(fmt::format("{} {}", kChannelNames[c], curve.label));
        if (reference) {
            auto* points = vtkPlotPoints::SafeDownCast(plot);
            if (points != nullptr) {
                points->SetMarkerStyle(vtkPlotPoints::CROSS);
                points->SetMarkerSize(6.0f);
            }
            // One legend entry for the reference, on its green points.
            plot->SetLegendVisibility(c == 1 && style_index == 0);
            plot->SetLabel("reference (path tracer), x");
        } else {
            plot->SetWidth(2.0f);
            plot->GetPen()->SetLineType(kLineStyles[style_index % 5]);
            // Colour is the channel; the line style is the curve: one legend entry per curve.
            plot->SetLegendVisibility(c == 1);
            plot->SetLabel(curve.label);
        }
        plot->GetXAxis();  // axes are the chart's
        plot->SetTooltipLabelFormat("{x}: {y}");
    }
}

std::vector<double> Range(double first, double last, int n) {
    std::vector<double> values(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
        values[static_cast<std::size_t>(i)] = first + (last - first) * i / (n - 1);
    return values;
}

void StyleChart(vtkChartXY* chart, const std::string& title, const std::string& x_title,
                const std::string& y_title) {
    chart->SetTitle(title);
    chart->GetTitleProperties()->SetFontSize(14);
    chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(x_title);
    chart->GetAxis(vtkAxis::LEFT)->SetTitle(y_title);
    chart->GetAxis(vtkAxis::BOTTOM)->GetTitleProperties()->SetFontSize(12);
    chart->GetAxis(vtkAxis::LEFT)->GetTitleProperties()->SetFontSize(12);
    chart->GetAxis(vtkAxis::BOTTOM)->GetLabelProperties()->SetFontSize(11);
    chart->GetAxis(vtkAxis::LEFT)->GetLabelProperties()->SetFontSize(11);
    chart->SetShowLegend(true);
    chart->GetLegend()->GetLabelProperties()->SetFontSize(10);
}

}  // namespace

vtkSmartPointer<vtkChartMatrix> MakeTransmittanceCharts(const Luts& luts,
                                                        const TransmittancePlotOptions& options) {
    const double top_km = (luts.atmosphere.top_radius - luts.atmosphere.bottom_radius) / kKm;
    const std::vector<double> zenith_samples =
        options.zenith_samples_deg.empty() ? Range(0.0, 180.0, 721) : options.zenith_samples_deg;
    std::vector<double> altitude_samples;
    for (double km : options.altitude_samples_km.empty() ? Range(0.0, top_km, 201)
                                                         : options.altitude_samples_km) {
        altitude_samples.push_back(km * kKm);
    }

    auto matrix = vtkSmartPointer<vtkChartMatrix>::New();
    matrix->SetSize(vtkVector2i(2, 1));
    matrix->SetGutter(vtkVector2f(60.0f, 30.0f));
    auto* by_zenith = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 0)));
    auto* by_altitude = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(1, 0)));
    const std::string name = luts.atmosphere.name;
    StyleChart(by_zenith, fmt::format("{}: transmittance to space vs view angle", name),
               "view zenith angle (deg)", "transmittance (red R, green G, blue B)");
    StyleChart(by_altitude, fmt::format("{}: transmittance to space vs altitude", name),
               "altitude (km)", "transmittance (red R, green G, blue B)");

    for (std::size_t i = 0; i < options.altitudes_km.size(); ++i) {
        const double altitude = options.altitudes_km[i] * kKm;
        AddCurve(by_zenith, TransmittanceVersusZenith(luts, altitude, zenith_samples),
                 static_cast<int>(i), false);
        if (options.reference) {
            std::vector<double> sparse;  // the reference is slower: every 5 deg, and near 90
            for (double a = 0.0; a <= 180.0; a += 5.0) sparse.push_back(a);
            for (double a : {86.0, 88.0, 89.0, 89.5, 91.0, 92.0, 93.0}) sparse.push_back(a);
            std::sort(sparse.begin(), sparse.end());
            AddCurve(by_zenith,
                     ReferenceTransmittanceVersusZenith(luts.atmosphere, altitude, sparse),
                     static_cast<int>(i), true);
        }
    }
    for (std::size_t i = 0; i < options.zeniths_deg.size(); ++i) {
        AddCurve(by_altitude,
                 TransmittanceVersusAltitude(luts, options.zeniths_deg[i], altitude_samples),
                 static_cast<int>(i), false);
        if (options.reference) {
            AddCurve(by_altitude,
                     ReferenceTransmittanceVersusAltitude(luts.atmosphere, options.zeniths_deg[i],
                                                          Range(0.0, top_km * kKm, 21)),
                     static_cast<int>(i), true);
        }
    }
    for (vtkChartXY* chart : {by_zenith, by_altitude}) {
        vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
        if (options.log) {
            y->SetLogScale(true);
            y->SetBehavior(vtkAxis::FIXED);
            y->SetRange(1e-4, 1.0);
        } else {
            y->SetBehavior(vtkAxis::FIXED);
            y->SetRange(0.0, 1.0);
        }
    }
    // Legends where the curves are not: under them on the left, to the lower right on the right.
    by_zenith->GetLegend()->SetHorizontalAlignment(vtkChartLegend::LEFT);
    by_zenith->GetLegend()->SetVerticalAlignment(vtkChartLegend::BOTTOM);
    by_altitude->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
    by_altitude->GetLegend()->SetVerticalAlignment(vtkChartLegend::BOTTOM);
    by_zenith->GetAxis(vtkAxis::BOTTOM)->SetBehavior(vtkAxis::FIXED);
    by_zenith->GetAxis(vtkAxis::BOTTOM)->SetRange(0.0, 120.0);
    return matrix;
}

std::vector<vtkTable*> ChartTables(vtkChartMatrix* charts, int column, bool reference) {
    std::vector<vtkTable*> tables;
    auto* chart = vtkChartXY::SafeDownCast(charts->GetChart(vtkVector2i(column, 0)));
    if (chart == nullptr) return tables;
    for (vtkIdType i = 0; i < chart->GetNumberOfPlots(); ++i) {
        vtkPlot* plot = chart->GetPlot(i);
        // vtkPlotLine derives from vtkPlotPoints: the reference is the points that are no line.
        const bool is_reference = vtkPlotPoints::SafeDownCast(plot) != nullptr &&
                                  vtkPlotLine::SafeDownCast(plot) == nullptr;
        if (is_reference != reference) continue;
        vtkTable* table = plot->GetInput();
        if (tables.empty() || tables.back() != table) tables.push_back(table);
    }
    return tables;
}

vtkSmartPointer<vtkImageData> SliceImage(const Slice& slice, bool log) {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(slice.width, slice.height, 1);
    image->SetOrigin(slice.x0, slice.y0, 0.0);
    image->SetSpacing(slice.dx, slice.dy, 1.0);
    image->AllocateScalars(VTK_DOUBLE, 1);
    auto* values = static_cast<double*>(image->GetScalarPointer());
    for (std::size_t i = 0; i < slice.values.size(); ++i) {
        const double v = slice.values[i];
        values[i] = log ? (v > 0.0 ? std::log10(v) : kNaN) : v;
    }
    image->GetPointData()->GetScalars()->SetName(log ? "log10_value" : "value");
    return image;
}

vtkSmartPointer<vtkAbstractContextItem> MakeSliceChart(const Slice& slice, bool log) {
    if (slice.height == 1) {
        // One-dimensional LUT: a line chart of the chosen channel.
        auto chart = vtkSmartPointer<vtkChartXY>::New();
        StyleChart(chart, slice.title, slice.x_title, slice.value_title);
        Curve curve;
        curve.label = "";
        auto table = vtkSmartPointer<vtkTable>::New();
        auto x = vtkSmartPointer<vtkDoubleArray>::New();
        x->SetName("x");
        auto y = vtkSmartPointer<vtkDoubleArray>::New();
        y->SetName("value");
        table->AddColumn(x);
        table->AddColumn(y);
        table->SetNumberOfRows(slice.width);
        for (int i = 0; i < slice.width; ++i) {
            table->SetValue(i, 0, slice.x0 + i * slice.dx);
            table->SetValue(i, 1, slice.values[static_cast<std::size_t>(i)]);
        }
        vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
        plot->SetInputData(table, 0, 1);
        plot->SetWidth(2.0f);
        plot->SetColor(0, 0, 0, 255);
        plot->SetLabel(slice.value_title);
        chart->GetAxis(vtkAxis::LEFT)->SetLogScale(log);
        chart->SetShowLegend(false);
        return chart;
    }
    const vtkSmartPointer<vtkImageData> image = SliceImage(slice, log);
    double range[2] = {0.0, 1.0};
    image->GetPointData()->GetScalars()->GetRange(range);  // NaN-free range
    if (!(range[1] > range[0])) range[1] = range[0] + 1.0;
    auto colours = vtkSmartPointer<vtkColorTransferFunction>::New();
    // "Inferno"-like ramp: dark for low values so that zero and NaN (grey) stay apart.
    const double stops[][3] = {{0.0, 0.0, 0.02},
                               {0.34, 0.06, 0.43},
                               {0.73, 0.21, 0.33},
                               {0.98, 0.55, 0.04},
                               {0.99, 1.0, 0.64}};
    for (int i = 0; i < 5; ++i) {
        colours->AddRGBPoint(range[0] + (range[1] - range[0]) * i / 4.0, stops[i][0], stops[i][1],
                             stops[i][2]);
    }
    colours->SetNanColor(0.6, 0.6, 0.6);
    colours->Build();

    auto chart = vtkSmartPointer<vtkChartHistogram2D>::New();
    chart->SetInputData(image);
    chart->SetTransferFunction(colours);
    chart->SetTitle(slice.title);
    chart->GetTitleProperties()->SetFontSize(14);
    const double x1 = slice.x0 + slice.dx * (slice.width - 1);
    const double y1 = slice.y0 + slice.dy * (slice.height - 1);
    chart->GetAxis(vtkAxis::BOTTOM)->SetBehavior(vtkAxis::FIXED);
    chart->GetAxis(vtkAxis::BOTTOM)->SetRange(slice.x0, x1);
    chart->GetAxis(vtkAxis::LEFT)->SetBehavior(vtkAxis::FIXED);
    chart->GetAxis(vtkAxis::LEFT)->SetRange(slice.y0, y1);
    chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(slice.x_title);
    chart->GetAxis(vtkAxis::LEFT)->SetTitle(slice.y_title);
    if (auto* legend = vtkColorLegend::SafeDownCast(chart->GetLegend())) {
        legend->SetTitle(log ? "log10 " + slice.value_title : slice.value_title);
    }
    return chart;
}

// --- export ----------------------------------------------------------------------------------

namespace {

vtkSmartPointer<vtkFloatArray> NewArray(const char* name, int components, vtkIdType tuples) {
    auto array = vtkSmartPointer<vtkFloatArray>::New();
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(tuples);
    return array;
}

void AddFieldString(vtkImageData* image, const char* name, const std::string& value) {
    auto array = vtkSmartPointer<vtkStringArray>::New();
    array->SetName(name);
    array->InsertNextValue(value);
    image->GetFieldData()->AddArray(array);
}

}  // namespace

vtkSmartPointer<vtkImageData> LutImageData(const Luts& luts, LutKind kind) {
    const sky::LutImage& lut = luts.Image(kind);
    const glm::ivec3 n = lut.size;
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(n.x, n.y, n.z);
    const auto count = static_cast<vtkIdType>(lut.texels.size());
    const auto rgba = NewArray("rgba", 4, count);
    const char* quantity = "value";
    switch (kind) {
        case LutKind::kTransmittance:
            quantity = "transmittance";
            break;
        case LutKind::kMultipleScattering:
            quantity = "psi_ms_and_moments";
            break;
        case LutKind::kIrradiance:
            quantity = "sky_irradiance_per_lux";
            break;
        case LutKind::kSkyView:
            quantity = "luminance_cd_m2";
            break;
        case LutKind::kAerialPerspective:
            quantity = "in_scattering_cd_m2";
            break;
    }
    const auto rgb = NewArray(quantity, 3, count);
    for (vtkIdType i = 0; i < count; ++i) {
        const glm::vec4& t = lut.texels[static_cast<std::size_t>(i)];
        rgba->SetTuple4(i, t.r, t.g, t.b, t.a);
        rgb->SetTuple3(i, t.r, t.g, t.b);
    }
    image->GetPointData()->AddArray(rgba);
    image->GetPointData()->AddArray(rgb);
    image->GetPointData()->SetActiveScalars(quantity);

    auto index = [&](int x, int y, int z) { return static_cast<vtkIdType>(lut.Index(x, y, z)); };
    const double top = luts.atmosphere.top_radius - luts.atmosphere.bottom_radius;
    std::string axes;
    switch (kind) {
        case LutKind::kTransmittance: {
            const auto altitude = NewArray("altitude_m", 1, count);
            const auto zenith = NewArray("view_zenith_deg", 1, count);
            for (int y = 0; y < n.y; ++y) {
                for (int x = 0; x < n.x; ++x) {
                    double r = 0.0, mu = 0.0;
                    TransmittanceTexelRMu(luts, x, y, &r, &mu);
                    altitude->SetValue(index(x, y, 0),
                                       static_cast<float>(r - luts.atmosphere.bottom_radius));
                    zenith->SetValue(index(x, y, 0), static_cast<float>(std::acos(mu) / kDeg));
                }
            }
            image->GetPointData()->AddArray(altitude);
            image->GetPointData()->AddArray(zenith);
            axes =
                "x: texel (distance to the top of the atmosphere, B17); y: texel (distance to "
                "the horizon); see altitude_m, view_zenith_deg";
            break;
        }
        case LutKind::kMultipleScattering: {
            const auto sun = NewArray("sun_zenith_deg", 1, count);
            const auto altitude = NewArray("altitude_m", 1, count);
            for (int y = 0; y < n.y; ++y) {
                for (int x = 0; x < n.x; ++x) {
                    double mu_s = 0.0, h = 0.0;
                    MultipleScatteringTexelMuSAltitude(luts, x, y, &mu_s, &h);
                    sun->SetValue(index(x, y, 0), static_cast<float>(std::acos(mu_s) / kDeg));
                    altitude->SetValue(index(x, y, 0), static_cast<float>(h));
                }
            }
            image->GetPointData()->AddArray(sun);
            image->GetPointData()->AddArray(altitude);
            image->SetSpacing(1.0, top / kKm / (n.y - 1), 1.0);
            axes =
                "x: texel (u = 0.5 + 0.5 sign(mu_s) sqrt|mu_s|) in three tiles side by side: "
                "rgb psi_ms, q_xx, q_zz (the incident light's second moments, z up, x toward "
                "the sun's azimuth), alpha q_xz's r, g, b; y: altitude in km; see "
                "sun_zenith_deg, altitude_m";
            break;
        }
        case LutKind::kIrradiance: {
            const auto sun = NewArray("sun_zenith_deg", 1, count);
            for (int x = 0; x < n.x; ++x) {
                sun->SetValue(index(x, 0, 0),
                              static_cast<float>(std::acos(IrradianceTexelMuS(luts, x)) / kDeg));
            }
            image->GetPointData()->AddArray(sun);
            image->SetOrigin(-1.0, 0.0, 0.0);
            image->SetSpacing(2.0 / (n.x - 1), 1.0, 1.0);
            axes = "x: cosine of the sun zenith angle mu_s; see sun_zenith_deg";
            break;
        }
        case LutKind::kSkyView: {
            const auto zenith = NewArray("view_zenith_deg", 1, count);
            const auto azimuth = NewArray("azimuth_from_sun_deg", 1, count);
            for (int y = 0; y < n.y; ++y) {
                for (int x = 0; x < n.x; ++x) {
                    double vz = 0.0, az = 0.0;
                    SkyViewTexelAngles(luts, x, y, &vz, &az);
                    zenith->SetValue(index(x, y, 0), static_cast<float>(vz / kDeg));
                    azimuth->SetValue(index(x, y, 0), static_cast<float>(az / kDeg));
                }
            }
            image->GetPointData()->AddArray(zenith);
            image->GetPointData()->AddArray(azimuth);
            image->SetOrigin(0.5 * 360.0 / n.x, 0.0, 0.0);
            image->SetSpacing(360.0 / n.x, 1.0, 1.0);
            axes =
                "x: azimuth from the sun in degrees; y: texel (non-linear in the view zenith "
                "angle, H20 §5.3); see view_zenith_deg";
            break;
        }
        case LutKind::kAerialPerspective: {
            const auto transmittance = NewArray("mean_transmittance", 1, count);
            const auto horizontal = NewArray("horizontal_angle_deg", 1, count);
            const auto vertical = NewArray("vertical_angle_deg", 1, count);
            const auto depth = NewArray("depth_m", 1, count);
            for (int z = 0; z < n.z; ++z) {
                for (int y = 0; y < n.y; ++y) {
                    for (int x = 0; x < n.x; ++x) {
                        double h = 0.0, v = 0.0;
                        AerialPerspectiveCellAngles(luts, x, y, &h, &v);
                        const vtkIdType i = index(x, y, z);
                        transmittance->SetValue(i, lut.at(x, y, z).a);
                        horizontal->SetValue(i, static_cast<float>(h / kDeg));
                        vertical->SetValue(i, static_cast<float>(v / kDeg));
                        depth->SetValue(i,
                                        static_cast<float>(AerialPerspectiveSliceDepth(luts, z)));
                    }
                }
            }
            for (const auto& a : {transmittance, horizontal, vertical, depth}) {
                image->GetPointData()->AddArray(a);
            }
            const double range_km = luts.settings.aerial_perspective_range / kKm;
            image->SetOrigin(0.0, 0.0, 0.5 * range_km / n.z);
            image->SetSpacing(1.0, 1.0, range_km / n.z);
            axes =
                "x, y: screen cells of the camera; z: depth of the slice centre in km; see "
                "horizontal_angle_deg, vertical_angle_deg, depth_m";
            break;
        }
    }
    AddFieldString(image, "lut", std::string(LutName(kind)));
    AddFieldString(image, "atmosphere", luts.atmosphere.name);
    AddFieldString(image, "axes", axes);
    AddFieldString(image, "gl", luts.gl_description);
    return image;
}

void WriteVti(vtkImageData* image, const std::filesystem::path& path) {
    auto writer = vtkSmartPointer<vtkXMLImageDataWriter>::New();
    writer->SetFileName(path.c_str());
    writer->SetInputData(image);
    writer->SetDataModeToBinary();
    if (writer->Write() != 1) throw Error("cannot write " + path.string());
}

vtkSmartPointer<vtkPolyData> FlightPath(const std::filesystem::path& flight, double step_s) {
    if (!(step_s > 0.0)) {
        throw ArgumentError(fmt::format("--step = {} s is out of range (expected > 0)", step_s));
    }
    const track::FlightLog log = track::ReadFlightLog(flight);
    const track::Trajectory trajectory(log);
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    auto lines = vtkSmartPointer<vtkCellArray>::New();
    auto time = vtkSmartPointer<vtkDoubleArray>::New();
    time->SetName("time_s");
    auto unix_time = vtkSmartPointer<vtkDoubleArray>::New();
    unix_time->SetName("unix_time_s");
    auto height = vtkSmartPointer<vtkDoubleArray>::New();
    height->SetName("height_m");
    auto lat = vtkSmartPointer<vtkDoubleArray>::New();
    lat->SetName("lat_deg");
    auto lon = vtkSmartPointer<vtkDoubleArray>::New();
    lon->SetName("lon_deg");
    auto sun = vtkSmartPointer<vtkDoubleArray>::New();
    sun->SetName("sun_elevation_deg");
    const geo::Ephemeris ephemeris;
    const double t0 = trajectory.start_time_s();
    for (const auto& [begin, end] : trajectory.ValidIntervals()) {
        std::vector<vtkIdType> ids;
        for (double t = begin;; t += step_s) {
            const double tt = std::min(t, end);
            const track::TrajectoryState s = trajectory.At(tt);
            if (s.valid) {
                ids.push_back(points->InsertNextPoint(s.ecef.x, s.ecef.y, s.ecef.z));
                time->InsertNextValue(tt - t0);
                unix_time->InsertNextValue(tt);
                height->InsertNextValue(s.height);
                lat->InsertNextValue(s.lat_deg);
                lon->InsertNextValue(s.lon_deg);
                const geo::SkyEphemeris e =
                    ephemeris.Compute(geo::TimeFromUtc(geo::CivilFromUnixSeconds(tt)),
                                      geo::Observer(s.lat_deg, s.lon_deg, s.height));
                sun->InsertNextValue(e.sun.elevation / kDeg);
            }
            if (tt >= end) break;
        }
        if (ids.size() >= 2) lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    }
    auto path = vtkSmartPointer<vtkPolyData>::New();
    path->SetPoints(points);
    path->SetLines(lines);
    for (const auto& a : {time, unix_time, height, lat, lon, sun})
        path->GetPointData()->AddArray(a);
    path->GetPointData()->SetActiveScalars("sun_elevation_deg");
    return path;
}

void WriteVtp(vtkPolyData* path, const std::filesystem::path& file) {
    auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    writer->SetFileName(file.c_str());
    writer->SetInputData(path);
    writer->SetDataModeToBinary();
    if (writer->Write() != 1) throw Error("cannot write " + file.string());
}

// --- overview --------------------------------------------------------------------------------

namespace {

vtkSmartPointer<vtkActor> Sphere(double radius, double r, double g, double b, double opacity) {
    auto source = vtkSmartPointer<vtkSphereSource>::New();
    source->SetRadius(radius);
    source->SetThetaResolution(96);
    source->SetPhiResolution(48);
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputConnection(source->GetOutputPort());
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(r, g, b);
    actor->GetProperty()->SetOpacity(opacity);
    return actor;
}

// An arrow of `length` from the origin along unit `direction`.
vtkSmartPointer<vtkActor> Arrow(const glm::dvec3& direction, double length, double r, double g,
                                double b) {
    auto source = vtkSmartPointer<vtkArrowSource>::New();
    source->SetShaftResolution(24);
    source->SetTipResolution(24);
    source->SetTipLength(0.08);
    source->SetTipRadius(0.025);
    source->SetShaftRadius(0.008);
    // vtkArrowSource points along +x: rotate +x onto direction, then scale.
    const glm::dvec3 x(1.0, 0.0, 0.0);
    const glm::dvec3 axis = glm::cross(x, direction);
    const double angle = std::atan2(glm::length(axis), glm::dot(x, direction)) / kDeg;
    auto transform = vtkSmartPointer<vtkTransform>::New();
    if (glm::length(axis) > 1e-12) {
        transform->RotateWXYZ(angle, axis.x, axis.y, axis.z);
    } else if (glm::dot(x, direction) < 0.0) {
        transform->RotateZ(180.0);
    }
    transform->Scale(length, length, length);
    auto filter = vtkSmartPointer<vtkTransformPolyDataFilter>::New();
    filter->SetTransform(transform);
    filter->SetInputConnection(source->GetOutputPort());
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputConnection(filter->GetOutputPort());
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(r, g, b);
    return actor;
}

}  // namespace

vtkSmartPointer<vtkRenderer> MakeOverview(const sky::Atmosphere& a, const Scene& scene,
                                          vtkPolyData* flight) {
    auto renderer = vtkSmartPointer<vtkRenderer>::New();
    renderer->SetBackground(0.02, 0.02, 0.06);
    renderer->AddActor(Sphere(a.bottom_radius, 0.25, 0.45, 0.3, 1.0));
    renderer->AddActor(Sphere(a.top_radius, 0.45, 0.65, 1.0, 0.18));

    // The observer: the scene's position, or the flight's first point and time.
    geo::Observer observer(scene.lat_deg, scene.lon_deg, scene.height_m);
    geo::Time time = geo::TimeFromIso8601(scene.utc);
    std::string when = scene.utc;
    if (flight != nullptr && flight->GetNumberOfPoints() > 0) {
        auto* lat = flight->GetPointData()->GetArray("lat_deg");
        auto* lon = flight->GetPointData()->GetArray("lon_deg");
        auto* height = flight->GetPointData()->GetArray("height_m");
        auto* unix_time = flight->GetPointData()->GetArray("unix_time_s");
        observer = geo::Observer(lat->GetTuple1(0), lon->GetTuple1(0), height->GetTuple1(0));
        const geo::CivilTime civil = geo::CivilFromUnixSeconds(unix_time->GetTuple1(0));
        time = geo::TimeFromUtc(civil);
        when = fmt::format("{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:02.0f}Z", civil.year, civil.month,
                           civil.day, civil.hour, civil.minute, civil.second);

        auto tube = vtkSmartPointer<vtkTubeFilter>::New();
        tube->SetInputData(flight);
        tube->SetRadius(0.003 * a.bottom_radius);
        tube->SetNumberOfSides(12);
        auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
        mapper->SetInputConnection(tube->GetOutputPort());
        mapper->ScalarVisibilityOff();
        auto actor = vtkSmartPointer<vtkActor>::New();
        actor->SetMapper(mapper);
        actor->GetProperty()->SetColor(1.0, 0.2, 0.1);
        renderer->AddActor(actor);
    }
    const geo::SkyEphemeris e = geo::Ephemeris().Compute(time, observer);
    const glm::dmat3 ecef_from_enu = observer.ecef_from_enu();
    const glm::dvec3 sun =
        glm::normalize(ecef_from_enu * e.sun.topocentric.horizontal.direction_enu);
    const glm::dvec3 moon =
        glm::normalize(ecef_from_enu * e.moon.topocentric.horizontal.direction_enu);
    renderer->AddActor(Arrow(sun, 2.0 * a.bottom_radius, 1.0, 0.85, 0.2));
    renderer->AddActor(Arrow(moon, 1.6 * a.bottom_radius, 0.75, 0.75, 0.8));

    // The observer as a small sphere on the surface.
    const glm::dvec3 up = ecef_from_enu[2];
    auto marker = Sphere(0.008 * a.bottom_radius, 1.0, 1.0, 1.0, 1.0);
    const glm::dvec3 at = up * (a.bottom_radius + observer.height_m());
    marker->SetPosition(at.x, at.y, at.z);
    renderer->AddActor(marker);

    auto text = vtkSmartPointer<vtkTextActor>::New();
    text->SetInput(fmt::format("{} ({}): planet R = {:.0f} km, atmosphere to {:.0f} km\n"
                               "{}  observer {:.2f}, {:.2f}, {:.0f} m\n"
                               "Sun (yellow) elevation {:.1f} deg, Moon (grey) {:.1f} deg"
                               "{}",
                               a.name, "ECEF, sphere at the planet centre", a.bottom_radius / kKm,
                               (a.top_radius - a.bottom_radius) / kKm, when, observer.lat_deg(),
                               observer.lon_deg(), observer.height_m(), e.sun.elevation / kDeg,
                               e.moon.elevation / kDeg,
                               flight != nullptr ? "; flight path (red)" : "")
                       .c_str());
    text->GetTextProperty()->SetFontSize(14);
    text->GetTextProperty()->SetColor(1.0, 1.0, 1.0);
    text->SetDisplayPosition(10, 10);
    renderer->AddViewProp(text);

    // Look at the observer from outside and from the side of the Sun's direction, so that the
    // arrows show in profile.
    vtkCamera* camera = renderer->GetActiveCamera();
    glm::dvec3 side = glm::cross(up, sun);
    side = glm::length(side) > 1e-6 ? glm::normalize(side) : glm::dvec3(0.0);
    const glm::dvec3 eye = glm::normalize(up * 1.5 + side) * (5.0 * a.bottom_radius);
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(eye.x, eye.y, eye.z);
    const glm::dvec3 view_up = std::abs(glm::dot(glm::normalize(eye), glm::dvec3(0, 0, 1))) < 0.95
                                   ? glm::dvec3(0, 0, 1)
                                   : glm::dvec3(0, 1, 0);
    camera->SetViewUp(view_up.x, view_up.y, view_up.z);
    renderer->ResetCameraClippingRange();
    return renderer;
}

// --- drawing ----------------------------------------------------------------------------------

namespace {

void SavePng(vtkRenderWindow* window, const std::filesystem::path& out) {
    window->Render();
    auto grab = vtkSmartPointer<vtkWindowToImageFilter>::New();
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    grab->Update();
    auto writer = vtkSmartPointer<vtkPNGWriter>::New();
    const std::filesystem::path partial = out.string() + ".partial.png";
    writer->SetFileName(partial.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    std::error_code error;
    if (!std::filesystem::exists(partial, error) || std::filesystem::file_size(partial) == 0) {
        throw Error("could not write " + out.string());
    }
    std::filesystem::rename(partial, out);  // never a half-written PNG under the final name
}

}  // namespace

void ShowChart(vtkAbstractContextItem* item, glm::ivec2 size, const std::filesystem::path& out) {
    auto view = vtkSmartPointer<vtkContextView>::New();
    view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
    view->GetRenderWindow()->SetSize(size.x, size.y);
    view->GetScene()->AddItem(item);
    if (!out.empty()) {
        view->GetRenderWindow()->SetOffScreenRendering(1);
        SavePng(view->GetRenderWindow(), out);
        return;
    }
    view->GetRenderWindow()->SetWindowName("zenith-plot");
    view->GetInteractor()->Initialize();
    view->GetInteractor()->Start();
}

void ShowScene(vtkRenderer* renderer, glm::ivec2 size, const std::filesystem::path& out) {
    auto window = vtkSmartPointer<vtkRenderWindow>::New();
    window->SetSize(size.x, size.y);
    window->AddRenderer(renderer);
    window->SetMultiSamples(0);
    if (!out.empty()) {
        window->SetOffScreenRendering(1);
        SavePng(window, out);
        return;
    }
    window->SetWindowName("zenith-plot overview");
    auto interactor = vtkSmartPointer<vtkRenderWindowInteractor>::New();
    interactor->SetRenderWindow(window);
    interactor->Initialize();
    interactor->Start();
}

}  // namespace zenith::vis
