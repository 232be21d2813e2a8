// VTK scenes of zenith-plot: transmittance curves, LUT slices with a colour bar, the .vti/.vtp
// exports and the 3-D overview. Building the data (tables, images, poly data) needs no display;
// only Render/Save do (see display.h).
#pragma once

#include <vtkSmartPointer.h>

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "luts.h"

class vtkChartMatrix;
class vtkChartXY;
class vtkAbstractContextItem;
class vtkImageData;
class vtkPolyData;
class vtkRenderer;
class vtkTable;

namespace zenith::vis {

struct TransmittancePlotOptions {
    std::vector<double> altitudes_km{0.0, 5.0, 10.0, 30.0};        // curves of the left chart
    std::vector<double> zeniths_deg{0.0, 60.0, 80.0, 85.0, 89.0};  // curves of the right chart
    // x samples: view zenith angles (deg) of the left chart and altitudes (km) of the right one;
    // empty: 0..180 deg in 0.25 deg steps and 0..top of the atmosphere in 200 steps.
    std::vector<double> zenith_samples_deg;
    std::vector<double> altitude_samples_km;
    bool reference = false;  // overlay the independent CPU reference (path_tracer.h) as points
    bool log = false;        // logarithmic transmittance axis
};

// Two vtkChartXY side by side: T(R, G, B) versus view zenith angle for each altitude, and
// versus altitude for each view zenith angle. Each line plot's input table has the columns
// "x" and "R", "G", "B" (the values drawn), so tests can read exactly what is plotted.
vtkSmartPointer<vtkChartMatrix> MakeTransmittanceCharts(const Luts& luts,
                                                        const TransmittancePlotOptions& options);
// The line plots' tables of one chart of the matrix (0: versus zenith, 1: versus altitude),
// reference tables excluded (reference == false) or only those (reference == true).
std::vector<vtkTable*> ChartTables(vtkChartMatrix* charts, int column, bool reference);

// An image of a slice with a colour bar (vtkChartHistogram2D), axes in physical units; log:
// log10 of the values. A one-row slice (the irradiance LUT) is drawn as a line chart instead.
vtkSmartPointer<vtkAbstractContextItem> MakeSliceChart(const Slice& slice, bool log);
vtkSmartPointer<vtkImageData> SliceImage(const Slice& slice, bool log);

// Every texel of a LUT as vtkImageData for ParaView: "rgba" (the texels exactly as read back
// from GL), a named RGB array for the quantity, and the physical coordinates of each texel
// centre from the renderer's inverse mappings. Spacing is physical along axes that are linear
// in a physical quantity and one texel otherwise; the field data "axes" says which.
vtkSmartPointer<vtkImageData> LutImageData(const Luts& luts, LutKind kind);
void WriteVti(vtkImageData* image, const std::filesystem::path& path);

// A flight log replayed through track::Trajectory every step_s seconds: ECEF polylines (one per
// valid stretch) with point data "time_s" (since the first fix), "unix_time_s", "height_m",
// "lat_deg", "lon_deg" and "sun_elevation_deg" (geo ephemeris, geometric).
vtkSmartPointer<vtkPolyData> FlightPath(const std::filesystem::path& flight, double step_s);
void WriteVtp(vtkPolyData* path, const std::filesystem::path& file);

// The planet, the atmosphere shell, Sun and Moon directions at `utc` seen from the observer
// (or from the flight's first fix) and the flight path, in ECEF metres.
vtkSmartPointer<vtkRenderer> MakeOverview(const sky::Atmosphere& atmosphere, const Scene& scene,
                                          vtkPolyData* flight);

// Draws the chart/scene: interactively when out is empty, else offscreen into the PNG `out`.
void ShowChart(vtkAbstractContextItem* item, glm::ivec2 size, const std::filesystem::path& out);
void ShowScene(vtkRenderer* renderer, glm::ivec2 size, const std::filesystem::path& out);

}  // namespace zenith::vis
