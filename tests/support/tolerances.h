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

/// One angle (radians, up to pi) from atan2 by two routes that differ only in which of its
/// arguments' candidates is picked (surface/triangle_geometry.h min_angle): glibc's atan2 is within
/// an ulp (~4e-16 at pi), so 1e-15 rad.
constexpr double kAtan2Rad = 1e-15;

/// Mesh volume of a smooth tissue against its voxel volume after CGAL meshing of a small
/// generated image: the surface sits between voxel staircase and the smoothed boundary, so a few
/// percent is the discretisation error at the coarse test sizes. The acceptance bound on the
/// phantom (3%) is tighter because its tissues are many voxels across.
constexpr double kSmallImageVolumeRel = 0.05;

/// Mesh volume of a 4 x 4 x 4-voxel block against its voxel volume at the coarse test sizes
/// (facet distance 0.3 of a voxel, smoothed labels): its edges and corners are rounded off, a
/// large share of so small a block; 25 % still tells a meshed block from a missing one.
constexpr double kSmallBlockVolumeRel = 0.25;

/// Volume of a tissue bounded by flat, axis-aligned interfaces and the image box: the surface is
/// exact up to CGAL's boundary search (relative error bound 1e-6 of the image diagonal), so only
/// round-off remains; 1e-6 relative.
constexpr double kFlatInterfaceVolumeRel = 1e-6;

/// Enclosed volume of an extracted multi-material surface (surface/surface_extraction.h) against
/// the voxel volume on the small test images: the surface stays in the half-voxel band around the
/// voxel boundary and Taubin relaxation does not shrink it; measured 0.4-1.9 % (worst: a 5-voxel
/// sphere). Plain Laplacian relaxation (no inflating mu step) exceeds 5 %, so 5 % still catches
/// shrinkage.
constexpr double kExtractedSurfaceVolumeRel = 0.05;

/// Per-tissue volume of the CGAL mesh of a surface complex against the volume the surface encloses:
/// the mesh's boundary triangles lie within facet_distance (a tenth of the mean edge h) of the
/// input surface, on both sides, and its vertices are on it; for balls of radius R = 5-9 mm at
/// h ~ 2 mm that bounds the change by about 3 d / R = 0.3 h / R ~ 12 % in the worst case, far
/// less on average; measured 0.3-1.3 % (boxes, outer ball) and 3.4 % (the inner 5 mm ball), all
/// losses (chords inside convex parts). A tissue dropped or merged is off by far more.
constexpr double kComplexMeshVolumeRel = 0.04;

/// The acceptance bound for the same tissue's mean displacement under gravity on two meshes
/// of the same geometry (CGAL or any mesh against TetGen's): discretisation error of tet10 on two
/// different meshes, not round-off (measured 3.4 % on the test block; tet4 locks differently on
/// each mesh and is not held to it).
constexpr double kCrossMeshDisplacementRel = 0.05;

/// Gmsh's element quality (gamma, SICN; values in [-1, 1]) against ours for the same tet: Gmsh
/// 4.8 writes them with "%g", 6 significant digits, so half a unit of the 6th digit (5e-7) plus
/// round-off; a different formula (e.g. an unsigned SICN, or the mean ratio instead of the
/// radius ratio) is off by 1e-2 or more.
constexpr double kGmshPrintedQualityAbs = 1e-6;

/// Smallest dihedral angle of a CGAL mesh of a test complex after exudation, sliver flips and
/// sliver smoothing (default VolumeMeshParams): the bound for the CGAL mesh itself;
/// measured 13.1 degrees (nested spheres) and 12.6 degrees (three boxes, where a needle boundary
/// facet beside the protected triple line kept a tet at 8.1 degrees until smoothing could slide
/// vertices within the flat box faces).
constexpr double kComplexMeshMinDihedralDeg = 10.0;

/// A surface vertex that constrained relaxation keeps on an axis-aligned plane or line (a flat
/// interface, a straight junction): its coordinate there is an average of equal values, clamped and
/// mapped to millimetres, so only a few ulps of ~20 mm of round-off remain; 1e-9 mm.
constexpr double kConstrainedCoordinateMm = 1e-9;

/// Symmetric Hausdorff distance of a remeshed surface to the extracted one, in voxel diagonals:
/// the acceptance bound itself (the remesher is given half of it as its approximation
/// bound, so a test at the full bound has room for the sampled measurement, not for a real loss
/// of shape: a collapsed sphere or a shaved junction corner is several diagonals off).
constexpr double kRemeshHausdorffVoxelDiagonals = 1.0;

/// Least gains of the mean-quality smoothing (two passes) on layers folding every three voxels at
/// 4,000 vertices: measured +0.0197 and +1.10 degrees (Q_av 0.8824 -> 0.9022, 50.41 -> 51.51 degrees).
constexpr double kMeanSmoothingQualityGain = 0.01;
constexpr double kMeanSmoothingAngleGainDeg = 0.5;

/// Central finite differences of smooth functions with step 1e-6 at unit-scale arguments:
/// truncation ~1e-12 and round-off ~1e-10 relative to the function scale; 1e-7 relative to the
/// size of the derivative separates a right formula from a wrong one (errors are O(1) then).
constexpr double kFiniteDifferenceRel = 1e-7;

/// Energy conjugacy along a finite path (solver element tests): Pi(u1) - Pi(u0) against the line
/// integral of f_int . (u1 - u0), integrated by composite 2-point Gauss-Legendre on 100 panels.
/// Its truncation is h^4/4320 times the integrand's 4th derivative, ~2e-12 of the integrand's
/// scale for a smooth path with O(1) derivatives (h = 1/100); round-off over 200 terms ~1e-14.
/// 1e-9 relative to the energy change leaves a 100x margin, while a force that is not the
/// energy's gradient misses by O(1).
constexpr double kPathIntegralRel = 1e-9;

/// Reference values quoted to 6-7 significant digits (the uniaxial table of docs/verification.md,
/// "Solver: analytic references": e.g. 501.419 Pa, 0.914705): half a unit in the last quoted digit
/// is at most 1.0e-6 relative in those tables (501.419 Pa +- 0.0005); 2e-6 covers that rounding
/// plus the bisection and round-off of the computed value and still catches a formula slip in the
/// fifth digit.
constexpr double kQuotedSixDigitsRel = 2e-6;

/// CalculiX (ccx 2.20) accepts a Newton iterate when the largest residual force is at most
/// R_n^alpha = 0.005 of the average nodal force (ccx manual "Convergence criteria"; ctrl[] default
/// 0.005 in ccx's main program, *CONTROLS PARAMETERS=FIELD). Weight itself is exact (GRAV acts on the
/// reference mass, which hyperelastic deformation keeps), so what separates the total support
/// reaction from the weight is the out-of-balance force ccx accepted: 0.005 of the load is the
/// relative size ccx's criterion would allow in the worst case, but residuals of a converged
/// iterate do not add up coherently: measured 1e-14 to 1e-11 on the block models and 1.2e-6 on
/// the coarse demo, where the .dat's 7 printed digits (5e-7 relative) dominate. 1e-5 keeps a
/// 10x margin over that and still catches a wrong density of any tissue holding more than 1e-5
/// of the mass (the demo's tumour holds 2.6e-3).
constexpr double kCalculixEquilibriumRel = 1e-5;

/// Values in a CalculiX .dat are printed as 1p,e13.6: 7 significant digits, i.e. a rounding of at
/// most 5e-7 relative per value. 1e-6 relative to the summed magnitudes covers sums and
/// differences of such values (the TOTALS line against the sum of the rows, n . u on a sliding
/// node) with a factor 2 of margin.
constexpr double kCalculixPrintRel = 1e-6;

/// Built-in solver: residual tolerance the equilibrium tests ask for (model.analysis.residual_tolerance),
/// relative to ||f_ext|| on the free dofs. The sum of all internal forces is zero to round-off (each
/// element's f_int sums to zero: sum_a grad N_a = 0), so total reaction + weight = -(sum of the free
/// residuals), at most sqrt(n_free) ||R|| <= sqrt(n_free) 1e-10 ||f_ext|| <= ~1e-10 W (||f_ext|| ~ W /
/// sqrt(n)). Newton reaches it in one or two extra quadratic iterations; round-off of f_int on the
/// block is ~1e-13 of the load, so 1e-10 is reachable and leaves 100x below kSolverEquilibriumRel.
constexpr double kSolverTightResidualRel = 1e-10;

/// Total reaction against total weight, relative: the acceptance figure (1e-8). A wrong
/// load (a missing tissue, a wrong density or unit) or a reaction taken without the load lumped on
/// the fixed nodes misses by >= 1e-3.
constexpr double kSolverEquilibriumRel = 1e-8;

/// Built-in solver: two solves of one model that reach its equilibrium by different routes (from
/// zero, from a given start, with a shared workspace), both to kSolverTightResidualRel and a
/// displacement correction below 1e-8: their displacements differ by at most the residual times
/// the compliance, ~1e-9 of the max displacement on the block (measured values are printed);
/// 1e-7 of it leaves margin, while a different equilibrium (5 % more load) differs by 5e-2.
constexpr double kSolverSameEquilibriumRel = 1e-7;

/// Built-in solver vs CalculiX on the same deck and energy: the acceptance figure, max
/// nodal difference <= 1% of the max displacement. Both solve the same discrete equations (same
/// shape functions and quadrature, C3D4 1 point, C3D10 4 points), so the difference is only the
/// convergence tolerance of each and ccx's 7 printed digits; measured values are printed.
constexpr double kCalculixSolutionRel = 0.01;

/// Linear response at tiny loads (gravity x 1e-6 and 3e-6): the nonlinear part of the response is
/// of relative size ~ strain ~ 1e-6 here (the full-load strain is O(1)), and Newton reaches the
/// residual tolerance 1e-6 of the load in one or two iterations of an almost linear problem, so the
/// ratio of the two solutions equals the load ratio to ~1e-6; 1e-4 keeps a 100x margin
/// while a load or stiffness that is not scaled consistently misses by O(1).
constexpr double kSmallLoadLinearityRel = 1e-4;

/// Reference values quoted to 4 decimals of a millimetre (the confined-column table of
/// tests/solver/test_verification.cpp, e.g. 16.8201 mm): the table rounds to half a unit of the
/// last digit, 5e-5 mm, and the value computed in the test (bisection + Gauss-Legendre,
/// tests/solver/column_reference.h) is exact to ~1e-12 mm, so no further margin is needed (the
/// largest measured gap is 4.1e-5 mm, 16.82006 vs 16.8201). A wrong volumetric form or modulus
/// misses by 1e-2 mm or more.
constexpr double kQuotedFourDecimalsMm = 5e-5;

/// Cell stresses of a homogeneous deformation (solver_check/cell_fields.h) against the law's closed
/// form, relative to the bulk modulus K (the largest stress scale, K >> mu): both routes evaluate
/// the same smooth functions of F = O(1) entries in double, so they differ by a few ulps of the
/// largest term, K (J - 1) ~ 1e-1 K, plus the pushforward F S F^T / J (~10 operations): ~1e-15 K.
/// Measured on the block: 5.6e-16 K (homogeneous stretch), 3.5e-15 K (40 degree rotation, where
/// C = R^T R = I only to round-off). 1e-12 K (5e-8 Pa at K = 50 kPa) leaves a 300x margin, while a
/// wrong pushforward (S instead of sigma) or a unit slip (MPa as Pa) misses by 1e-3 K or more.
/// Also used, absolutely, for J.
constexpr double kStressRoundoffRel = 1e-12;

/// Total reaction against total weight after a solve with the default residual tolerance
/// (model.analysis.residual_tolerance = 1e-6 of ||f_ext,free||), relative to the weight W. Every
/// element's f_int sums to zero, so reaction + weight = -(sum of the free residuals), whose norm is
/// at most sqrt(n_free) ||R_free|| <= sqrt(n_free) 1e-6 ||f_ext,free||; a load spread over the
/// nodes has ||f_ext|| ~ W / sqrt(n), so the imbalance is at most ~1e-6 W. Residuals of a converged
/// Newton iterate do not add up coherently and Newton usually overshoots the tolerance
/// quadratically, so this worst case leaves margin; a wrong density, unit or a missing tissue's
/// load misses by >= 1e-3. (kSolverEquilibriumRel is the acceptance figure at a tighter tolerance.)
constexpr double kSolverDefaultEquilibriumRel = 1e-6;

/// The same model solved in two unit systems (mm-t-s, SI, mm-kg-s), reported in mm: in exact
/// arithmetic the Newton iterates are the same up to the unit scale and every convergence test is a
/// scale-free ratio, so the same increments and iterations are taken and the results differ only
/// by round-off (~1e-13 relative, amplified by the tangent's condition, ~1e4 on the block). 1e-6 of
/// the largest displacement covers that with margin, while a units slip misses by a factor >= 1e3.
constexpr double kUnitSystemSolveRel = 1e-6;

/// Observed convergence rate log2(e(h) / e(h/2)) on the last refinement of a uniformly refined
/// structured mesh against the a-priori order (tet4 2, tet10 3 in L2 and at the column tip): the
/// higher-order terms still shift it on the meshes a unit test can afford; measured deviations
/// are at most 0.19 (tet4 column tip 1.81, hanging (J-1)^2 nu = 0.3; tet10 2.85 in L2; tet4 bar
/// 1.90). 0.3 accepts those, while a lost order (a wrong load integration, a constraint that leaks,
/// a stiffness that does not converge to the law's) deviates by ~1, and a wrong law or a missing
/// Poisson coupling makes the error stall at O(1) (rate ~0).
constexpr double kConvergenceRateSlack = 0.3;

/// Linear part of the response of the neo-Hookean laws at small load, extracted from solves at
/// gravity scales s and 2s as (4 u(s) - u(2s)) / (2s), against the exact quadratic linear-elastic
/// field of the hanging bar that tet10 contains: what remains is the O(s^2) remainder, ~eps^2
/// relative with eps ~ 1.5e-4 the largest strain (measured 0.8e-8 lnJ, 2.3e-8 (J-1)^2), the solver
/// tolerance (kSolverTightResidualRel) and the stress round-off ~1e-16/eps. 1e-6 keeps a 40x margin
/// and is still 7000x below the finest tet4 error of the same problem (7e-3): a tet10 that only
/// converged, rather than reproduced the field, would miss it.
constexpr double kLinearPartRel = 1e-6;

/// A homogeneous finite-strain state reproduced by the solver (uniaxial stress on a cube of straight
/// tet4/tet10 elements, which contain it exactly) against its independently computed reference:
/// only the Newton tolerance (kSolverTightResidualRel) and round-off separate them; a residual of
/// 1e-10 of the reaction scale moves the 27-125 nodes of the cube by ~1e-10 x a condition number
/// below 100, so 1e-9 relative (stretches, P11) holds, measured <= 3e-11. A law whose lateral
/// stress at the reference state is off by 1e-8 of mu already fails it.
constexpr double kHomogeneousStateRel = 1e-9;

/// Nodal-pressure tet4 against tet10 on the same nearly incompressible mesh: both are locking-free
/// discretisations of one problem and differ by their discretisation errors. Max sag of the block
/// fixture (2 mm grid): nodal tet4 9.4 % below tet10; refined to 1 mm, 3.0 % (tet10 itself moves
/// 0.8 %), while the standard tet4 is 48 % and 37 % below: 15 % separates the two by 3x.
constexpr double kLockingFreeRel = 0.15;

/// Smallest angle of the remeshed triangles touching the small junction loops of
/// island_under_layer() at budgets 100-150: measured 16.2-21.7 degrees with the size cap around
/// stuck junction edges, 11.2-13.5 without it; 15 separates the two.
constexpr double kGradedLoopMinAngleDeg = 15.0;

/// Smallest angle of the whole remeshed island_under_layer() at budget 300: measured 21.74
/// degrees with the pattern search of the angle smoothing (surface/remesh_sweeps.cpp), 18.27
/// without it; 20 separates the two. (23.06 since the smoothing repeats until nothing moves.)
constexpr double kPolishedMinAngleDeg = 20.0;
/// Smallest angle of the remeshed island_under_layer() at budget 400: measured 23.06 degrees
/// with the angle smoothing repeated until a pass moves nothing (surface/surface_remesh.cpp), 19.85
/// with three passes; 21.5 separates the two.
constexpr double kRepeatedPolishMinAngleDeg = 21.5;
/// Smallest angle of the remeshed island_under_layer() at budget 200: measured 26.11 degrees when
/// the angle smoothing may hand input vertices to a neighbour (surface/remesh_complex.h
/// keeps_represented), 18.38 when it may not; 22 separates the two.
constexpr double kHandoffMinAngleDeg = 22.0;

/// A quality the remesher prints to 4 decimals in a progress note ("Q_min 0.3222 -> 0.3469")
/// against the value computed from the surface: half a unit of the last printed digit.
constexpr double kPrintedFourDecimals = 5e-5;

/// A triangular solve in single precision (solver_check/single_precision_factor.h) against the
/// double-precision solve of the same well-conditioned test matrix (condition number < 10):
/// float's unit round-off 6e-8 times the few terms per entry and the condition number stays below
/// 1e-6; 1e-5 leaves margin, while a lost or misdirected update is off by 1e-2 or more.
constexpr double kSinglePrecisionSolveRel = 1e-5;

}  // namespace tissuemesh::test
