// The one place where test tolerances live. Every tolerance says why it has its value.
#pragma once

namespace tissuemesh::test {

/// Coordinates computed by different but exact routes (e.g. the same voxel grid read from NIfTI,
/// NRRD or MetaImage): they differ only by float32 header storage (NIfTI stores the affine in
/// float32; 2^-24 relative on ~200 mm coordinates is ~1.2e-5 mm), so 1e-4 mm is safe and still
/// a thousand times smaller than any voxel.
constexpr double kHeaderCoordinateMm = 1e-4;

/// Sums of many double terms (volumes, areas): relative round-off well below 1e-12 for the sizes
/// used in tests; 1e-9 leaves margin without hiding a wrong formula.
constexpr double kRelativeRoundoff = 1e-9;

/// Angles from closed-form references (e.g. the regular tetrahedron's dihedral acos(1/3)):
/// only double round-off separates the two; 1e-9 degrees.
constexpr double kAngleDeg = 1e-9;

/// Mesh volume of a smooth tissue against its voxel volume after CGAL meshing of a small
/// generated image: the surface sits between voxel staircase and the smoothed boundary, so a few
/// percent is the discretisation error at the coarse test sizes. The acceptance bound on the
/// phantom (3%) is tighter because its tissues are many voxels across.
constexpr double kSmallImageVolumeRel = 0.05;

/// Volume of a tissue bounded by flat, axis-aligned interfaces and the image box: the surface is
/// exact up to CGAL's boundary search (relative error bound 1e-6 of the image diagonal), so only
/// round-off remains; 1e-6 relative.
constexpr double kFlatInterfaceVolumeRel = 1e-6;

/// Central finite differences of smooth functions with step 1e-6 at unit-scale arguments:
/// truncation ~1e-12 and round-off ~1e-10 relative to the function scale; 1e-7 relative to the
/// size of the derivative separates a right formula from a wrong one (errors are O(1) then).
constexpr double kFiniteDifferenceRel = 1e-7;

}  // namespace tissuemesh::test
