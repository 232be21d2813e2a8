// The reflectance and transmittance of a homogeneous non-absorbing plane-parallel slab over a
// black ground, lit by a collimated beam, for the clouds' dual-lobe Henyey-Greenstein phase
// function: the exact fluxes (to the quadrature's accuracy, ~1e-4) that the renderer's
// delta-Eddington diffuse field is fitted to at a grazing Sun (CloudSlabTables).
//
// Method: adding-doubling (van de Hulst 1980, "Multiple Light Scattering", Ch. 4; Hansen &
// Travis 1974, Space Sci. Rev. 16, §3.2) of the azimuth-averaged radiance on kSlabStreams
// Gauss-Legendre cosines per hemisphere, the phase function delta-M scaled (Wiscombe 1977,
// J. Atmos. Sci. 34) to its first 2 kSlabStreams Legendre moments. A layer thin enough that
// the light in it scatters once (optical depth <= 2^-30) is doubled until it is the slab; the
// beam's diffuse light is doubled alongside as a source whose lower half sees the beam
// attenuated by the upper half. Only fluxes are wanted, which the azimuthal mean carries
// whole. Independent of the cloud path tracer (reference/cloud_path_tracer.h), which checks it
// (tests/sky/slab_transfer_test.cpp, cloud_reference_report --part grazing).
#pragma once

#include <vector>

namespace zenith::sky {

inline constexpr int kSlabStreams = 16;

struct SlabTransfer {
    double reflectance;    // upward flux at the top / the beam's flux mu0 E on it
    double transmittance;  // downward flux at the base, direct and diffuse, / mu0 E
};

// Fluxes through a slab of optical depth `optical_depth` (> 0) for each beam cosine in `mu0`
// (each in (0, 1]), the phase function (1 - w) p_hg(g0) + w p_hg(g1), g0 and g1 in (-1, 1),
// w in [0, 1]. About 1 ms.
std::vector<SlabTransfer> ConservativeSlabTransfer(double forward_g, double backward_g,
                                                   double lobe_weight, double optical_depth,
                                                   const std::vector<double>& mu0);

}  // namespace zenith::sky
